#pragma once
// A capture's frame as Live Link Face's 61 values: ARKit's 52 blend shapes,
// then the head's yaw, pitch and roll and each eye's, in radians, in the
// order of Unreal's EARFaceBlendShape (the order of the app's UDP stream,
// livelink_packet.hpp; its CSV takes, livelink_csv.hpp, order a few apart).
// The ICT model's 53 weights map onto the shapes by name: eyeBlink_L is
// EyeBlinkLeft, the shapes ICT splits that ARKit does not (browInnerUp,
// cheekPuff) are the mean of their halves, and TongueOut, which ICT lacks, is 0.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "facecap/core/geometry.hpp"

namespace facecap {

struct LiveLinkPose {
  Vec3d head_yaw_pitch_roll_deg = Vec3d::Zero();  // yaw_pitch_roll_deg of the head's rotation
  Vec2d left_eye_deg = Vec2d::Zero();             // gaze (yaw, pitch) of the subject's left eye
  Vec2d right_eye_deg = Vec2d::Zero();
};

class LiveLinkFace {
 public:
  static constexpr int kValues = 61;
  static constexpr int kShapes = 52;  // the first kValues; the angles follow
  using Values = std::array<float, kValues>;

  // `expression_names`: the model's, in its order.
  explicit LiveLinkFace(const std::vector<std::string>& expression_names);

  // In names()' order; a value that is not finite is 0.
  Values values(const Eigen::VectorXf& weights, const LiveLinkPose& pose) const;

  // EyeBlinkLeft ... TongueOut, HeadYaw ... RightEyeRoll: Unreal's EARFaceBlendShape.
  static const std::array<std::string_view, kValues>& names();
  // The index of `name` in names(); -1 where it is none of them.
  static int index_of(std::string_view name);

 private:
  // For each ARKit shape, the model weights whose mean it is (none: 0).
  std::vector<std::vector<int>> sources_;
};

}  // namespace facecap
