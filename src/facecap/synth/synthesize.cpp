#include "facecap/synth/synthesize.hpp"

#include <chrono>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/synth/synth_renderer.hpp"

namespace facecap {

namespace fs = std::filesystem;

SynthJobResult synthesize(const FaceModel& model, const SynthOptions& options, const fs::path& out_dir, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  options.check();
  ensure_writable_dir(out_dir);
  SynthJobResult result;
  result.video = out_dir / "video.mp4";
  result.truth = out_dir / "truth.json";
  result.albedo = out_dir / "albedo.png";

  SynthTruth& truth = result.ground_truth;
  truth.performance = make_performance(model, options);
  if (options.render_frames > 0) truth.performance.frames.resize(size_t(options.render_frames));
  truth.expression_names = model.expression_names;
  const SynthRenderer renderer(model, truth.performance);

  SyntheticMark mark;
  mark.kind = "synthetic-render";
  mark.parameters = {{"seed", std::to_string(options.seed)},
                     {"frames", std::to_string(options.frames)},
                     {"detail", options.detail ? "true" : "false"}};
  if (options.render_frames > 0) mark.parameters["rendered_frames"] = std::to_string(options.render_frames);
  if (options.face_texture.empty()) {
    mark.description = "A face rendered from the ICT face model with known parameters; no real person.";
  } else {
    // The shape and motion are drawn, but the skin is a real person's.
    mark.description =
        "A face rendered from the ICT face model with known parameters, its skin texture taken from a photo of a "
        "real person.";
    if (options.face_texture_source.empty()) {
      mark.parameters["face_texture"] = "given";
    } else {
      mark.sources.push_back(options.face_texture_source);
      mark.parameters["face_texture"] = std::filesystem::path(options.face_texture_source).filename().string();
    }
  }
  VideoWriterOptions vo;
  vo.width = options.width;
  vo.height = options.height;
  vo.fps = options.fps;
  vo.encoding.crf = 12;  // near-lossless: the renders are test inputs
  vo.metadata = synthetic_metadata(mark);
  VideoWriter writer(result.video, vo);

  std::mt19937_64 noise_rng(options.seed * 104729ull + 3);
  Progress progress("synth", int(truth.performance.frames.size()), quiet);
  for (const SynthFrame& frame : truth.performance.frames) {
    writer.write(renderer.render(frame, noise_rng));
    truth.landmarks.push_back(renderer.landmarks(frame));
    truth.vertex_landmarks.push_back(renderer.landmark_vertex_projections(frame));
    progress.update(frame.index + 1);
  }
  progress.finish();
  writer.finish();
  write_synthetic_sidecar(result.video, mark);
  write_truth(result.truth, truth);

  cv::Mat albedo8;
  renderer.appearance().face_texture.convertTo(albedo8, CV_8UC3, 255.0);
  write_image(result.albedo, albedo8);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace facecap
