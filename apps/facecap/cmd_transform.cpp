#include <cstdio>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/pipeline/transform_job.hpp"

namespace facecap::cli {

void register_transform(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand("transform",
                                 "Change a speaking face's expression (anger, disgust, fear, happiness, sadness, "
                                 "surprise, neutral) with the lips kept in sync; writes a video marked as synthetic");
  struct Args {
    std::string input, output, to = "happiness", from = "neutral", method = "cyclegan", schedule, plot, gltf, models;
    double intensity = 1.0;
    int window = 1;
    TransformJobOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUT", a->input, "Video file, image folder or cam:N")->required();
  cmd->add_option("-o,--output", a->output,
                  "Output video (.mp4, .m4v, .mov or .mkv), or for a photo also an image (.png, .jpg, .jpeg) marked "
                  "as synthetic in its metadata; OUT.json is its synthetic-media sidecar")
      ->required();
  cmd->add_option("--to", a->to, "Target expression")->capture_default_str();
  cmd->add_option("--from", a->from, "Source expression of the input")->capture_default_str();
  cmd->add_option("--intensity", a->intensity, "Share of the change, 0..1")->capture_default_str();
  cmd->add_option("--schedule", a->schedule, "File of 'seconds target intensity' keys with transitions between them");
  cmd->add_option("--method", a->method, "cyclegan, or the linear baseline of eq. 5.5")
      ->check(CLI::IsMember({"cyclegan", "linear"}))
      ->capture_default_str();
  cmd->add_option("--window", a->window, "Smoothing window half-width k (2k + 1 frames)")->capture_default_str();
  cmd->add_option("--plot", a->plot, "Write a PNG of weight curves (tracked, mapped, lip-corrected, smoothed)");
  cmd->add_option("--gltf", a->gltf,
                  "Also write the transformed performance as an animated glTF (.glb, as track --gltf; marked as "
                  "synthetic, with a sidecar .json). An input that cuts gets one per shot: OUT_shot<N>.glb after "
                  "the first");
  cmd->add_option("--models", a->models, "Expression models folder (default: models/expressions)");
  cmd->add_option("--max-frames", a->options.capture.max_frames, "Stop after this many frames (0: all)");
  add_start_option(*cmd, a->options.capture.start_seconds);
  add_init_frames_option(*cmd, a->options.capture.fit.init_frames);
  add_shot_cuts_option(*cmd, a->options.capture.shot_cuts);
  add_identity_option(*cmd, a->options.capture.fit.known_identity);
  add_face_option(*cmd, a->options.capture.tracker.pick);
  cmd->callback([a, &global] {
    const auto to = parse_emotion(a->to), from = parse_emotion(a->from);
    if (!to) throw Error("--to must be one of neutral, anger, disgust, fear, happiness, sadness, surprise");
    if (!from) throw Error("--from must be one of neutral, anger, disgust, fear, happiness, sadness, surprise");
    if (!(a->intensity >= 0 && a->intensity <= 1)) throw Error("--intensity must be between 0 and 1");
    if (a->window < 0 || a->window > 10) throw Error("--window must be between 0 and 10");
    TransformJobOptions& o = a->options;
    o.transform.from = *from;
    o.transform.schedule =
        a->schedule.empty() ? ExpressionSchedule::constant(*to, a->intensity) : ExpressionSchedule::read(a->schedule);
    o.transform.method = a->method == "linear" ? MappingMethod::kLinear : MappingMethod::kCycleGan;
    o.transform.window = a->window;
    o.plot = a->plot;
    o.gltf = a->gltf;
    if (!a->models.empty()) o.models_dir = a->models;
    o.description = a->schedule.empty() ? a->from + " to " + a->to : "schedule " + a->schedule;
    o.capture.quiet = global.quiet;
    const FaceModel model = load_model(global);
    const TransformSummary s = run_transform(model, a->input, a->output, o);
    const double n = std::max(1, s.timings.frames);
    std::fprintf(stderr,
                 "frames %d, lost %d | per frame: mapping+smoothing+QP %.2f ms, lighting %.2f ms, re-render+composite "
                 "%.2f ms\nwrote %s and %s.json (synthetic-media marks)\n",
                 s.capture.frames, s.capture.lost, s.timings.mapping_ms / n, s.timings.lighting_ms / n,
                 s.timings.render_ms / n, a->output.c_str(), a->output.c_str());
    if (const std::string note = unreadable_frames_note(s.capture, a->input); !note.empty())
      std::fprintf(stderr, "facecap: %s (black in the output)\n", note.c_str());
    for (const std::filesystem::path& file : s.animation_files)
      std::fprintf(stderr, "wrote %s and %s.json\n", file.c_str(), file.c_str());
  });
}

}  // namespace facecap::cli
