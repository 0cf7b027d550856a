#pragma once
// Expression transformation of a tracked sequence (§5.3), frame by frame
// with a delay of k frames: each frame's tracked weights are mapped to the
// scheduled target (scaled by its intensity), averaged over a window of
// 2k + 1 frames weighted by the discriminator's confidence, and corrected so
// that the key lip vertices stay where the source put them (eq. 5.4).
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "facecap/expr/expression_mapper.hpp"
#include "facecap/expr/expression_schedule.hpp"
#include "facecap/expr/lip_correction.hpp"

namespace facecap {

struct TransformOptions {
  Emotion from = Emotion::kNeutral;
  ExpressionSchedule schedule = ExpressionSchedule::constant(Emotion::kHappiness, 1.0);
  MappingMethod method = MappingMethod::kCycleGan;
  int window = 1;  // k of eq. 5.4: 2k + 1 frames
  // A FACS edit (`transform --units`, action_units.hpp) in place of the
  // mapping to an emotion: these shapes (model indices) set to these
  // weights in every frame, the rest as tracked; the schedule's intensity
  // still scales the change (its targets are not used). Then smoothed and
  // lip-corrected as a mapping is.
  std::vector<std::pair<int, float>> shape_targets;
  // Shapes (model indices) held as tracked whatever the mapping says,
  // unless shape_targets sets them: the gaze's eyeLook shapes
  // (eye_look.hpp; FaceTransformStream holds them). An expression does not
  // change where the speaker looks, and ICT's eyeLook shapes move the lids
  // (eyeLookDown at 1 lowers the upper lid 7.7 mm): the mappings, which
  // learnt nothing of gaze, moved them a little, enough to close the eyes
  // that surprise's eyeWide opens.
  std::vector<int> kept_shapes;
  LipCorrectionOptions lips;
};

struct TransformedFrame {
  int index = 0;
  double time = 0;
  bool valid = false;        // false: no face; the frame passes through
  Eigen::VectorXf tracked;   // the source weights
  Eigen::VectorXf mapped;    // per-frame mapping (at the scheduled intensity)
  Eigen::VectorXf lip_only;  // mapped + lip correction, no smoothing
  Eigen::VectorXf smoothed;  // window mean of the mapped weights
  Eigen::VectorXf weights;   // the result: smoothed + lip correction
};

class ExpressionTransformer {
 public:
  ExpressionTransformer(const ExpressionMapper& mapper, Eigen::MatrixXd lip_rows, TransformOptions options);

  std::vector<TransformedFrame> push(int index, double time, const std::optional<Eigen::VectorXf>& tracked);
  std::vector<TransformedFrame> finish();

 private:
  struct Slot {
    TransformedFrame frame;
    float confidence = 1.0f;
  };
  TransformedFrame complete(size_t at);
  Eigen::VectorXf map_scheduled(const Eigen::VectorXf& w, double time, float& confidence) const;
  MappedWeights with_shapes_set(const Eigen::VectorXf& w) const;               // options_.shape_targets
  void keep_shapes(Eigen::VectorXf& w, const Eigen::VectorXf& tracked) const;  // kept_ as in `tracked`

  const ExpressionMapper& mapper_;
  Eigen::MatrixXd lip_rows_;
  TransformOptions options_;
  std::vector<int> kept_;    // options_.kept_shapes less those shape_targets sets
  std::deque<Slot> window_;  // frames not yet output and the k before them
  int emitted_ = 0;          // frames of window_ already output (the past half)
};

}  // namespace facecap
