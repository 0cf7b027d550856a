#include "facecap/io/nuke_chan.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

namespace facecap {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
}

// Ry(b) Rx(a) Rz(c) = [[cb cc + sb sa sc, sb sa cc - cb sc, sb ca],
//                      [ca sc,            ca cc,            -sa  ],
//                      [cb sa sc - sb cc, sb sc + cb sa cc, cb ca]].
Vec3d euler_zxy_degrees(const Mat3d& m) {
  const double ca = std::hypot(m(1, 0), m(1, 1));
  const double a = std::atan2(-m(1, 2), ca);  // accurate near +-90 degrees too, where asin is not
  double b = 0, c = 0;
  if (ca > 1e-12) {
    b = std::atan2(m(0, 2), m(2, 2));
    c = std::atan2(m(1, 0), m(1, 1));
  } else {  // ca = 0: only b - c (sa = 1) or b + c (sa = -1) is seen; c = 0
    b = std::atan2(-m(2, 0), m(0, 0));
  }
  return Vec3d(a, b, c) / kDegree;
}

Mat3d rotation_from_euler_zxy_degrees(const Vec3d& degrees) {
  const Vec3d r = degrees * kDegree;
  return (Eigen::AngleAxisd(r.y(), Vec3d::UnitY()) * Eigen::AngleAxisd(r.x(), Vec3d::UnitX()) *
          Eigen::AngleAxisd(r.z(), Vec3d::UnitZ()))
      .toRotationMatrix();
}

std::string chan_line(int frame, const Vec3d& translate, const Vec3d& rotate_deg, std::optional<double> vfov_deg) {
  char line[256];
  int n = std::snprintf(line, sizeof line, "%d %.6f %.6f %.6f %.6f %.6f %.6f", frame, translate.x(), translate.y(),
                        translate.z(), rotate_deg.x(), rotate_deg.y(), rotate_deg.z());
  if (vfov_deg) n += std::snprintf(line + n, sizeof line - size_t(n), " %.6f", *vfov_deg);
  return std::string(line, size_t(n)) + "\n";
}

}  // namespace facecap
