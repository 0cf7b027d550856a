#pragma once
// Layout of a frame's parameter block in the Ceres problems: axis-angle
// rotation (3), translation in cm (3), then the expression weights. One block
// per frame lets the multi-frame identity solve eliminate frames with a Schur
// complement (a residual may touch only one eliminated block).
#include <vector>

#include "facecap/core/camera.hpp"

namespace facecap {

namespace frame_block {
inline constexpr int kRotation = 0;
inline constexpr int kTranslation = 3;
inline constexpr int kExpression = 6;
inline int size(int num_expressions) { return kExpression + num_expressions; }
}  // namespace frame_block

struct FrameParameters {
  std::vector<double> values;  // frame_block layout

  explicit FrameParameters(int num_expressions = 0) : values(frame_block::size(num_expressions), 0.0) {}
  int num_expressions() const { return static_cast<int>(values.size()) - frame_block::kExpression; }
  HeadPose pose() const {
    HeadPose p;
    p.rotation = Vec3d(values[0], values[1], values[2]);
    p.translation = Vec3d(values[3], values[4], values[5]);
    return p;
  }
  void set_pose(const HeadPose& p) {
    for (int k = 0; k < 3; ++k) {
      values[frame_block::kRotation + k] = p.rotation[k];
      values[frame_block::kTranslation + k] = p.translation[k];
    }
  }
  Eigen::Map<Eigen::VectorXd> expression() { return {values.data() + frame_block::kExpression, num_expressions()}; }
  Eigen::Map<const Eigen::VectorXd> expression() const {
    return {values.data() + frame_block::kExpression, num_expressions()};
  }
};

}  // namespace facecap
