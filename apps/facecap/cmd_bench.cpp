#include <thread>

#include "commands.hpp"
#include "facecap/pipeline/capture_session.hpp"

namespace facecap::cli {

namespace {

nlohmann::json timings_json(const StageTimings& t) {
  const double n = std::max(1, t.frames);
  return {{"frames", t.frames},
          {"setup_ms", t.setup_ms},
          {"decode_ms_per_frame", t.decode_ms / n},
          {"detect_ms_per_frame", t.detect_ms / n},
          {"landmarks_ms_per_frame", t.landmarks_ms / n},
          {"fit_ms_per_frame", t.fit_ms / n},
          {"identity_solve_ms", t.identity_ms},
          {"total_s", t.total_s},
          {"fps", t.fps()},
          {"fps_including_setup", t.total_s > 0 ? t.frames / t.total_s : 0.0},
          {"note", "decode runs on its own thread, concurrently with detection, landmarks and fit"}};
}

}  // namespace

void register_bench(CLI::App& app, GlobalOptions& global) {
  auto* bench = app.add_subcommand("bench", "Measure speed: per-stage milliseconds and frames per second (JSON)");
  bench->require_subcommand(1);
  auto* track = bench->add_subcommand("track", "Coarse tracking of an input, no output files");
  struct Args {
    std::string input;
    CaptureOptions capture;
  };
  auto a = std::make_shared<Args>();
  track->add_option("INPUT", a->input, "Video file, image folder or cam:N")->required();
  track->add_option("--max-frames", a->capture.max_frames, "Stop after this many frames (0: all)");
  track->callback([a, &global] {
    const FaceModel model = load_model(global);
    auto source = open_input(a->input);
    a->capture.quiet = true;
    const CaptureSummary s = run_capture(model, *source, a->capture, [](const CapturedFrame&) {});
    nlohmann::json j = timings_json(s.timings);
    j["input"] = a->input;
    j["width"] = s.input.width;
    j["height"] = s.input.height;
    j["lost_frames"] = s.lost;
    j["cores"] = std::thread::hardware_concurrency();
    print_json(j);
  });
}

}  // namespace facecap::cli
