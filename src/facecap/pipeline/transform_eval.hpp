#pragma once
// `facecap eval transform --video PATH --to EMOTION`: runs the expression
// transformation on real footage and measures what chapter 5 promises: the
// lips stay where the speaker put them, the target emotion's defining weights
// rise, the window smoothing makes the curves calmer than the per-frame
// mapping, and the output keeps the input's audio. With `--units AU1=4,...`
// (a FACS edit, `transform --units`) the same of that edit, and for each unit
// the intensity asked, the input's, the output's and what tracking the output
// again reads.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/expr/action_units.hpp"
#include "facecap/pipeline/transform_job.hpp"

namespace facecap {

// One unit of a FACS edit, its intensities (0-5, action_units.hpp) meaned
// over the valid frames.
struct UnitEditMeasure {
  ActionUnitTarget asked;  // the unit and the intensity set
  double input = 0;        // as the input was tracked
  double output = 0;       // the edit's weights (the lip correction may hold a unit that moves the lips back)
  double retracked = 0;    // the output tracked again with the input's identity held (TransformEval::retracked_rise)
};

struct TransformEval {
  int frames = 0;
  int valid_frames = 0;
  double lip_error_mm = 0;  // mean distance of the 4 key lip vertices to the source's
  double lip_error_max_mm = 0;
  double target_rise = 0;  // mean rise of the target's defining weights over the source's
  // The same rise as the tracker sees it in the output: the output tracked
  // again with the input's identity held (as `track --identity`; solved
  // afresh, an output that keeps its new expression throughout takes part of
  // it into the identity), its defining weights' mean against the input's
  // tracked ones. The fit of 68 landmarks reads part of a change as other
  // shapes, so this is lower than target_rise (README).
  double retracked_rise = 0;
  // How much wider the eyes look in the output than in the input: the mean
  // eye aspect ratio of dlib's landmarks on the output over the input's
  // (both tracked with the input's identity held), less 1. Surprise and
  // fear widen the eyes (eyeWide), happiness and anger narrow them.
  double eye_opening_change = 0;
  // Mean |change| of the gaze's eyeLook weights, result against tracked
  // (0: the edit keeps where the speaker looks; TransformOptions::kept_shapes).
  double gaze_change = 0;
  double smoothness = 0;  // mean |w_t - w_(t-1)| of the result
  // The same of the output without the smoothing term: the per-frame mapping
  // with the same lip correction. This is the ablation of the window
  // smoothing; the lip correction re-imports the speech motion of the
  // tracked lips into both, so the bare mapping (below) is calmer than either.
  double smoothness_raw = 0;
  double smoothness_mapped = 0;  // the bare per-frame mapping, no lip correction
  bool input_audio = false;
  bool audio_ok = false;  // output audio as long as the input's (over the frames processed)
  double audio_seconds_in = 0, audio_seconds_out = 0;
  bool marked_synthetic = false;       // container tag and sidecar present
  std::vector<UnitEditMeasure> units;  // a FACS edit's (evaluate_unit_edit): one per unit set
  TransformTimings timings;
};

// Metrics of a finished transformation (no I/O).
struct TransformMetrics {
  double lip_error_mm = 0, lip_error_max_mm = 0, target_rise = 0, smoothness = 0, smoothness_raw = 0;
  double smoothness_mapped = 0;
  double gaze_change = 0;
  int valid_frames = 0;
};
TransformMetrics measure_transform(const FaceModel& model, const std::vector<TransformedFrame>& frames, Emotion target);
// The same with the rise taken over the model's shapes `shapes` (none: 0).
TransformMetrics measure_transform(const FaceModel& model, const std::vector<TransformedFrame>& frames,
                                   const std::vector<int>& shapes);

// Each frame's weights as `track` fits a video (lost frames left out), and
// the identity it solved or held (capture.fit.known_identity): what
// retracked_rise reads an output with.
struct TrackedWeights {
  std::vector<Eigen::VectorXf> weights;
  std::vector<double> eye_openings;  // per frame, eye_aspect_ratio of dlib's landmarks
  Eigen::VectorXd identity;
};

// The eye aspect ratio of 68 landmarks (Soukupova and Cech, 2016): each
// eye's two lid-to-lid distances over twice its corners' distance, meaned
// over the eyes; 0 where an eye has no width.
double eye_aspect_ratio(const Landmarks& points);
TrackedWeights track_weights(const FaceModel& model, const std::filesystem::path& video, CaptureOptions capture);

// Writes the output to `output` (a temporary file when empty) and measures it.
TransformEval evaluate_transform(const FaceModel& model, const std::string& video, Emotion target,
                                 const TransformJobOptions& options, const std::filesystem::path& output = {});
// The same of a FACS edit setting `units` in every frame (`transform
// --units`): `units` has each unit's intensities; target_rise and
// retracked_rise stay 0 (an edit may set a unit lower, so a mean over its
// shapes would say little).
TransformEval evaluate_unit_edit(const FaceModel& model, const std::string& video,
                                 const std::vector<ActionUnitTarget>& units, const TransformJobOptions& options,
                                 const std::filesystem::path& output = {});

}  // namespace facecap
