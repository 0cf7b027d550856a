#include "facecap/core/camera.hpp"

namespace facecap {

Positions to_camera(const Positions& model, const HeadPose& pose) {
  const Mat3f r = pose.model_to_camera_rotation().cast<float>();
  const Vec3f t = pose.translation.cast<float>();
  Positions out = r * model;
  out.colwise() += t;
  return out;
}

}  // namespace facecap
