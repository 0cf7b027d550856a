#include "facecap/core/geometry.hpp"

#include <cmath>

namespace facecap {

namespace {
constexpr double kDeg = 180.0 / 3.14159265358979323846;
}

Vec3d yaw_pitch_roll_deg(const Mat3d& r) {
  // R = Ry(a) Rx(b) Rz(c): r(1,2) = -sin b, r(0,2) = sin a cos b, r(2,2) = cos a cos b,
  // r(1,0) = cos b sin c, r(1,1) = cos b cos c.
  const double pitch = std::asin(std::clamp(-r(1, 2), -1.0, 1.0));
  const double yaw = std::atan2(r(0, 2), r(2, 2));
  const double roll = std::atan2(r(1, 0), r(1, 1));
  return {yaw * kDeg, pitch * kDeg, roll * kDeg};
}

Mat3d rotation_from_yaw_pitch_roll_deg(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw / kDeg, Vec3d::UnitY()) * Eigen::AngleAxisd(pitch / kDeg, Vec3d::UnitX()) *
          Eigen::AngleAxisd(roll / kDeg, Vec3d::UnitZ()))
      .toRotationMatrix();
}

}  // namespace facecap
