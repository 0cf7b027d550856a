#include "facecap/pipeline/transform_eval.hpp"

#include <cmath>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"

namespace facecap {

namespace {

// Mean over weights and consecutive valid frames of |w_t - w_(t-1)|.
template <typename Get>
double mean_step(const std::vector<TransformedFrame>& frames, Get get) {
  double sum = 0;
  long count = 0;
  for (size_t i = 1; i < frames.size(); ++i) {
    if (!frames[i].valid || !frames[i - 1].valid) continue;
    sum += (get(frames[i]) - get(frames[i - 1])).cwiseAbs().mean();
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

// The model's indices of the target's defining shapes (emotions.hpp).
std::vector<int> defining_indices(const FaceModel& model, Emotion target) {
  std::vector<int> defining;
  for (const std::string& name : defining_shapes(target)) {
    const int k = model.expression_index(name);
    if (k >= 0) defining.push_back(k);
  }
  return defining;
}

// Mean of the target's defining weights over weight vectors.
double defining_mean(const FaceModel& model, const std::vector<Eigen::VectorXf>& weights, Emotion target) {
  double sum = 0;
  long count = 0;
  for (int k : defining_indices(model, target))
    for (const Eigen::VectorXf& w : weights) sum += w[k], ++count;
  return count > 0 ? sum / count : 0.0;
}

// TransformEval::retracked_rise.
double retracked_rise(const FaceModel& model, const TransformSummary& s, const std::filesystem::path& output,
                      Emotion target, CaptureOptions capture) {
  std::vector<Eigen::VectorXf> before;
  for (const TransformedFrame& f : s.frames)
    if (f.valid) before.push_back(f.tracked);
  if (before.empty()) return 0.0;
  capture.start_seconds = 0;  // the output begins where the input's run did
  capture.fit.known_identity = s.capture.identity.identity;
  const TrackedWeights after = track_weights(model, output, capture);
  return after.weights.empty() ? 0.0
                               : defining_mean(model, after.weights, target) - defining_mean(model, before, target);
}

}  // namespace

TransformMetrics measure_transform(const FaceModel& model, const std::vector<TransformedFrame>& frames,
                                   Emotion target) {
  TransformMetrics m;
  const Eigen::MatrixXd lips = lip_basis(model);  // 12 x E, cm per unit weight
  const std::vector<int> defining = defining_indices(model, target);
  double lip_sum = 0, rise_sum = 0;
  long lip_count = 0, rise_count = 0;
  for (const TransformedFrame& f : frames) {
    if (!f.valid) continue;
    ++m.valid_frames;
    // The model is linear: the key lip vertices move by B (w - w_source).
    const Eigen::VectorXd moved = lips * (f.weights - f.tracked).cast<double>();
    for (int v = 0; v < 4; ++v) {
      const double mm = 10.0 * moved.segment<3>(3 * v).norm();
      lip_sum += mm;
      m.lip_error_max_mm = std::max(m.lip_error_max_mm, mm);
      ++lip_count;
    }
    for (int k : defining) {
      rise_sum += f.weights[k] - f.tracked[k];
      ++rise_count;
    }
  }
  m.lip_error_mm = lip_count > 0 ? lip_sum / lip_count : 0.0;
  m.target_rise = rise_count > 0 ? rise_sum / rise_count : 0.0;
  m.smoothness = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.weights; });
  m.smoothness_raw = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.lip_only; });
  m.smoothness_mapped = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.mapped; });
  return m;
}

TrackedWeights track_weights(const FaceModel& model, const std::filesystem::path& video, CaptureOptions capture) {
  TrackedWeights out;
  capture.quiet = true;
  auto source = open_input(video.string());
  const CaptureSummary summary = run_capture(model, *source, capture, [&](const CapturedFrame& f) {
    if (f.status != TrackStatus::kLost) out.weights.push_back(f.fit.expression);
  });
  out.identity = summary.identity.identity;
  return out;
}

TransformEval evaluate_transform(const FaceModel& model, const std::string& video, Emotion target,
                                 const TransformJobOptions& options, const std::filesystem::path& output) {
  std::optional<TempDir> temp;
  std::filesystem::path out = output;
  if (out.empty()) {
    temp.emplace("facecap-eval-transform");
    out = temp->path() / "transformed.mp4";
  }
  TransformJobOptions o = options;
  o.transform.schedule = ExpressionSchedule::constant(target, 1.0);
  const TransformSummary s = run_transform(model, video, out, o);
  const TransformMetrics m = measure_transform(model, s.frames, target);

  TransformEval r;
  r.frames = static_cast<int>(s.frames.size());
  r.valid_frames = m.valid_frames;
  r.lip_error_mm = m.lip_error_mm;
  r.lip_error_max_mm = m.lip_error_max_mm;
  r.target_rise = m.target_rise;
  r.smoothness = m.smoothness;
  r.smoothness_raw = m.smoothness_raw;
  r.smoothness_mapped = m.smoothness_mapped;
  r.timings = s.timings;

  const InputInfo in = probe_video_file(video);
  r.input_audio = in.audio;
  const InputInfo result = probe_video_file(out);
  const double fps = in.fps > 0 ? in.fps : 25.0;
  // The input's audio (ending with the output's last frame when --max-frames
  // stopped the run early), against the output's.
  const double audio_in = in.audio_duration > 0 ? in.audio_duration : in.duration;
  const bool cut = output_like(in, o.capture.max_frames).audio_ends_with_video;
  const double video_out = result.fps > 0 ? result.frames / result.fps : result.duration;
  r.audio_seconds_in = in.audio ? (cut ? std::min(audio_in, video_out) : audio_in) : 0;
  r.audio_seconds_out = result.audio ? result.audio_duration : 0;
  // One frame of slack: AAC frames are 1024 samples (21-23 ms) and the encoder pads.
  r.audio_ok = in.audio && result.audio && std::abs(r.audio_seconds_out - r.audio_seconds_in) <= 1.0 / fps + 0.05;
  r.marked_synthetic = carries_synthetic_marks(out);
  r.retracked_rise = retracked_rise(model, s, out, target, o.capture);
  return r;
}

}  // namespace facecap
