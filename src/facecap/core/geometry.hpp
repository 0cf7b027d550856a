#pragma once
// Small geometric vocabulary shared by every stage: Eigen aliases and
// axis-angle rotations.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace facecap {

using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Vec2d = Eigen::Vector2d;
using Vec3d = Eigen::Vector3d;
using Mat3f = Eigen::Matrix3f;
using Mat3d = Eigen::Matrix3d;
// Vertex positions of a mesh, one column per vertex; memory is x0 y0 z0 x1 ...
using Positions = Eigen::Matrix3Xf;

// Cosine of the angle between a camera-space surface normal and the ray from
// the point back to the camera at the origin: 1 facing it, <= 0 facing away.
inline float view_facing(const Vec3f& camera_point, const Vec3f& normal) {
  return -normal.dot(camera_point) / std::max(1e-12f, normal.norm() * camera_point.norm());
}

// 0 up to `edge0`, 1 from `edge1`, Hermite-smooth between (no kink where a
// fade starts or ends).
inline float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// Rotation matrix of an axis-angle vector (direction = axis, norm = angle in radians).
inline Mat3d rotation_from_axis_angle(const Vec3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12) return Mat3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

inline Vec3d axis_angle_from_rotation(const Mat3d& r) {
  const Eigen::AngleAxisd aa(r);
  return aa.axis() * aa.angle();
}

// Angle in degrees of the relative rotation between two rotation matrices.
inline double rotation_angle_deg(const Mat3d& a, const Mat3d& b) {
  const double c = std::clamp(((a.transpose() * b).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / 3.14159265358979323846;
}

// Angle in degrees between two directions (any lengths but zero).
inline double angle_between_deg(const Vec3d& a, const Vec3d& b) {
  const double c = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
  return std::acos(c) * 180.0 / 3.14159265358979323846;
}

// Yaw (about y), pitch (about x) and roll (about z) in degrees of a head
// rotation, for reports; R = Ry(yaw) * Rx(pitch) * Rz(roll).
Vec3d yaw_pitch_roll_deg(const Mat3d& r);
Mat3d rotation_from_yaw_pitch_roll_deg(double yaw, double pitch, double roll);

}  // namespace facecap
