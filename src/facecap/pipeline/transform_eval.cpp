#include "facecap/pipeline/transform_eval.hpp"

#include <cmath>
#include <optional>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/model/eye_look.hpp"

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

// The output tracked again as TransformEval::retracked_rise says: from its
// first frame, with the identity the input's run solved held.
TrackedWeights retrack(const FaceModel& model, const TransformSummary& s, const std::filesystem::path& output,
                       CaptureOptions capture) {
  capture.start_seconds = 0;  // the output begins where the input's run did
  capture.fit.known_identity = s.capture.identity.identity;
  return track_weights(model, output, capture);
}

// TransformEval::eye_opening_change: the input tracked again as the output
// was (`after`, retrack), over the same frames, both eyes' aspect ratios
// meaned.
double eye_opening_change(const FaceModel& model, const TransformSummary& s, const std::string& input,
                          const TrackedWeights& after, CaptureOptions capture) {
  capture.fit.known_identity = s.capture.identity.identity;
  const TrackedWeights before = track_weights(model, input, capture);
  auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (const double x : v) sum += x;
    return v.empty() ? 0.0 : sum / double(v.size());
  };
  const double in = mean(before.eye_openings);
  return in > 0 && !after.eye_openings.empty() ? mean(after.eye_openings) / in - 1.0 : 0.0;
}

// The input's tracked weights over its valid frames.
std::vector<Eigen::VectorXf> tracked_input(const TransformSummary& s) {
  std::vector<Eigen::VectorXf> input;
  for (const TransformedFrame& f : s.frames)
    if (f.valid) input.push_back(f.tracked);
  return input;
}

// Mean intensity of each unit over weight vectors (action_units() order).
Eigen::VectorXd mean_intensities(const ActionUnitReader& reader, const std::vector<Eigen::VectorXf>& weights) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(reader.size());
  for (const Eigen::VectorXf& w : weights) sum += reader.intensities(w);
  return weights.empty() ? sum : Eigen::VectorXd(sum / double(weights.size()));
}

// A run of the job and what every edit is measured by.
struct MeasuredRun {
  std::optional<TempDir> temp;  // holds the output when none was asked for
  std::filesystem::path output;
  TransformSummary summary;
  TransformEval eval;
};

// Runs the job into `output` (a temporary file when empty) and measures
// what every edit is measured by: frames, the lips, smoothness, the rise
// over `shapes`, the audio and the marks.
MeasuredRun run_and_measure(const FaceModel& model, const std::string& video, const TransformJobOptions& o,
                            const std::filesystem::path& output, const std::vector<int>& shapes) {
  MeasuredRun run;
  run.output = output;
  if (run.output.empty()) {
    run.temp.emplace("facecap-eval-transform");
    run.output = run.temp->path() / "transformed.mp4";
  }
  run.summary = run_transform(model, video, run.output, o);
  const TransformSummary& s = run.summary;
  const TransformMetrics m = measure_transform(model, s.frames, shapes);

  TransformEval& r = run.eval;
  r.frames = static_cast<int>(s.frames.size());
  r.valid_frames = m.valid_frames;
  r.lip_error_mm = m.lip_error_mm;
  r.lip_error_max_mm = m.lip_error_max_mm;
  r.target_rise = m.target_rise;
  r.smoothness = m.smoothness;
  r.smoothness_raw = m.smoothness_raw;
  r.smoothness_mapped = m.smoothness_mapped;
  r.gaze_change = m.gaze_change;
  r.timings = s.timings;

  const InputInfo in = probe_video_file(video);
  r.input_audio = in.audio;
  const InputInfo result = probe_video_file(run.output);
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
  r.marked_synthetic = carries_synthetic_marks(run.output);
  return run;
}

}  // namespace

TransformMetrics measure_transform(const FaceModel& model, const std::vector<TransformedFrame>& frames,
                                   Emotion target) {
  return measure_transform(model, frames, defining_indices(model, target));
}

TransformMetrics measure_transform(const FaceModel& model, const std::vector<TransformedFrame>& frames,
                                   const std::vector<int>& defining) {
  TransformMetrics m;
  const Eigen::MatrixXd lips = lip_basis(model);  // 12 x E, cm per unit weight
  const std::vector<int> gaze = EyeLookShapes(model).indices();
  double lip_sum = 0, rise_sum = 0, gaze_sum = 0;
  long lip_count = 0, rise_count = 0, gaze_count = 0;
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
    for (const int k : gaze) gaze_sum += std::abs(f.weights[k] - f.tracked[k]), ++gaze_count;
  }
  m.gaze_change = gaze_count > 0 ? gaze_sum / gaze_count : 0.0;
  m.lip_error_mm = lip_count > 0 ? lip_sum / lip_count : 0.0;
  m.target_rise = rise_count > 0 ? rise_sum / rise_count : 0.0;
  m.smoothness = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.weights; });
  m.smoothness_raw = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.lip_only; });
  m.smoothness_mapped = mean_step(frames, [](const TransformedFrame& f) -> const Eigen::VectorXf& { return f.mapped; });
  return m;
}

double eye_aspect_ratio(const Landmarks& p) {
  double sum = 0;
  int eyes = 0;
  for (const int first : {36, 42}) {
    // Corners first + 0 and + 3; upper lid + 1, + 2 over lower lid + 5, + 4.
    const double width = (p[first] - p[first + 3]).norm();
    if (!(width > 0)) continue;
    sum += ((p[first + 1] - p[first + 5]).norm() + (p[first + 2] - p[first + 4]).norm()) / (2 * width);
    ++eyes;
  }
  return eyes > 0 ? sum / eyes : 0.0;
}

TrackedWeights track_weights(const FaceModel& model, const std::filesystem::path& video, CaptureOptions capture) {
  TrackedWeights out;
  capture.quiet = true;
  auto source = open_input(video.string());
  const CaptureSummary summary = run_capture(model, *source, capture, [&](const CapturedFrame& f) {
    if (f.status == TrackStatus::kLost) return;
    out.weights.push_back(f.fit.expression);
    out.eye_openings.push_back(eye_aspect_ratio(f.fit.observed));
  });
  out.identity = summary.identity.identity;
  return out;
}

TransformEval evaluate_transform(const FaceModel& model, const std::string& video, Emotion target,
                                 const TransformJobOptions& options, const std::filesystem::path& output) {
  TransformJobOptions o = options;
  o.transform.schedule = ExpressionSchedule::constant(target, 1.0);
  MeasuredRun run = run_and_measure(model, video, o, output, defining_indices(model, target));
  TransformEval& r = run.eval;
  const std::vector<Eigen::VectorXf> before = tracked_input(run.summary);
  if (!before.empty()) {
    const TrackedWeights after = retrack(model, run.summary, run.output, o.capture);
    if (!after.weights.empty())
      r.retracked_rise = defining_mean(model, after.weights, target) - defining_mean(model, before, target);
    r.eye_opening_change = eye_opening_change(model, run.summary, video, after, o.capture);
  }
  return r;
}

TransformEval evaluate_unit_edit(const FaceModel& model, const std::string& video,
                                 const std::vector<ActionUnitTarget>& units, const TransformJobOptions& options,
                                 const std::filesystem::path& output) {
  if (units.empty()) throw Error("a FACS edit needs at least one unit");
  const ActionUnitReader reader(model.expression_names);
  TransformJobOptions o = options;
  o.transform.shape_targets = reader.shape_weights(units);
  MeasuredRun run = run_and_measure(model, video, o, output, {});
  TransformEval& r = run.eval;
  std::vector<Eigen::VectorXf> edited;
  for (const TransformedFrame& f : run.summary.frames)
    if (f.valid) edited.push_back(f.weights);
  const std::vector<Eigen::VectorXf> before = tracked_input(run.summary);
  const Eigen::VectorXd input = mean_intensities(reader, before), result = mean_intensities(reader, edited);
  const Eigen::VectorXd again =
      before.empty() ? Eigen::VectorXd::Zero(reader.size())
                     : mean_intensities(reader, retrack(model, run.summary, run.output, o.capture).weights);
  for (const ActionUnitTarget& unit : units) {
    const int u = action_unit_index(unit.number);
    r.units.push_back({unit, input[u], result[u], again[u]});
  }
  return r;
}

}  // namespace facecap
