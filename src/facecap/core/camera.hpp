#pragma once
// Pinhole camera and rigid head pose (paper §3.3, eq. 4.2).
//
// Camera frame: x right, y down, z forward (OpenCV convention), units cm.
// Model frame (ICT): x toward the subject's left, y up, z out of the face, cm.
// A head looking straight at the camera has rotation R = I: the model is first
// flipped into the camera convention, X_cam = R * F * X_model + t with
// F = diag(1, -1, -1), so priors and temporal terms act near the identity.
#include "facecap/core/geometry.hpp"

namespace facecap {

struct PinholeCamera {
  double focal = 1000.0;  // f_x = f_y, pixels (square pixels)
  double cx = 0.0;        // principal point, pixels (the image centre)
  double cy = 0.0;

  static PinholeCamera centered(double focal, int width, int height) { return {focal, 0.5 * width, 0.5 * height}; }
  // Eq. 4.2: (i, j) = (f X/Z + c_x, f Y/Z + c_y).
  Vec2d project(const Vec3d& p) const { return {focal * p.x() / p.z() + cx, focal * p.y() / p.z() + cy}; }
  Vec2f project(const Vec3f& p) const {
    return {float(focal) * p.x() / p.z() + float(cx), float(focal) * p.y() / p.z() + float(cy)};
  }
  // The same camera for a window of the image whose top-left pixel is (x0, y0).
  PinholeCamera cropped(double x0, double y0) const { return {focal, cx - x0, cy - y0}; }
  // The same camera for the image resized by `factor` (2: twice as fine; 0.5:
  // half). Pixel x covers [x - 0.5, x + 0.5], so it becomes (x + 0.5) factor
  // - 0.5: at factor 2, fine pixels 2x and 2x + 1 average to x.
  PinholeCamera resized(double factor) const {
    return {focal * factor, (cx + 0.5) * factor - 0.5, (cy + 0.5) * factor - 0.5};
  }
};

struct HeadPose {
  Vec3d rotation = Vec3d::Zero();     // axis-angle, radians
  Vec3d translation{0.0, 0.0, 60.0};  // cm, camera frame

  Mat3d rotation_matrix() const { return rotation_from_axis_angle(rotation); }
  // R * F: maps model coordinates to camera-frame directions.
  Mat3d model_to_camera_rotation() const {
    Mat3d rf = rotation_matrix();
    rf.col(1) *= -1.0;
    rf.col(2) *= -1.0;
    return rf;
  }
};

// Transforms model-space positions into camera space.
Positions to_camera(const Positions& model, const HeadPose& pose);

}  // namespace facecap
