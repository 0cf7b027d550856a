#include "facecap/core/geometry.hpp"

#include <gtest/gtest.h>

#include "facecap/core/camera.hpp"

namespace facecap {

TEST(Geometry, AxisAngleRoundTripsThroughRotationMatrix) {
  const Vec3d w(0.3, -0.2, 0.1);
  const Vec3d back = axis_angle_from_rotation(rotation_from_axis_angle(w));
  EXPECT_NEAR((back - w).norm(), 0.0, 1e-12);
  EXPECT_TRUE(rotation_from_axis_angle(Vec3d::Zero()).isIdentity());
}

TEST(Geometry, YawPitchRollRoundTrip) {
  const Mat3d r = rotation_from_yaw_pitch_roll_deg(25.0, -8.0, 4.0);
  const Vec3d ypr = yaw_pitch_roll_deg(r);
  EXPECT_NEAR(ypr.x(), 25.0, 1e-9);
  EXPECT_NEAR(ypr.y(), -8.0, 1e-9);
  EXPECT_NEAR(ypr.z(), 4.0, 1e-9);
}

TEST(Geometry, RotationAngleBetweenMatrices) {
  const Mat3d a = rotation_from_yaw_pitch_roll_deg(10, 0, 0);
  const Mat3d b = rotation_from_yaw_pitch_roll_deg(13, 0, 0);
  EXPECT_NEAR(rotation_angle_deg(a, b), 3.0, 1e-9);
}

TEST(Camera, ProjectsWithEquation42) {
  const PinholeCamera cam = PinholeCamera::centered(800.0, 640, 480);
  const Vec2d p = cam.project(Vec3d(10.0, -5.0, 100.0));
  EXPECT_DOUBLE_EQ(p.x(), 800.0 * 0.1 + 320.0);
  EXPECT_DOUBLE_EQ(p.y(), 800.0 * -0.05 + 240.0);
}

// An image resized by a factor keeps each pixel's area: at 2x, the fine
// pixels 2x and 2x + 1 cover coarse pixel x, so a point at coarse x lies at
// fine 2x + 0.5; resizing back returns the camera; a crop then a resize is a
// window of the image scaled.
TEST(Camera, AResizedCameraKeepsEachPixelsArea) {
  const PinholeCamera cam = PinholeCamera::centered(800.0, 640, 480);
  const Vec3d point(10.0, -5.0, 100.0);
  const Vec2d coarse = cam.project(point);
  EXPECT_NEAR((cam.resized(2.0).project(point) - (2.0 * coarse + Vec2d(0.5, 0.5))).norm(), 0.0, 1e-9);
  EXPECT_NEAR((cam.resized(0.25).project(point) - ((coarse + Vec2d(0.5, 0.5)) / 4.0 - Vec2d(0.5, 0.5))).norm(), 0.0,
              1e-9);
  const PinholeCamera back = cam.resized(4.0).resized(0.25);
  EXPECT_DOUBLE_EQ(back.focal, cam.focal);
  EXPECT_DOUBLE_EQ(back.cx, cam.cx);
  EXPECT_DOUBLE_EQ(back.cy, cam.cy);
  const Vec2d window = cam.cropped(100, 50).resized(0.5).project(point);
  EXPECT_NEAR((window - ((coarse - Vec2d(100, 50) + Vec2d(0.5, 0.5)) * 0.5 - Vec2d(0.5, 0.5))).norm(), 0.0, 1e-9);
}

TEST(Camera, FrontalHeadFacesTheCamera) {
  // The model's +z (out of the face) must point toward the camera (-z) at R = I,
  // and the model's up (+y) must point up in the image (-y).
  HeadPose pose;
  const Mat3d rf = pose.model_to_camera_rotation();
  EXPECT_NEAR((rf * Vec3d::UnitZ() - Vec3d(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rf * Vec3d::UnitY() - Vec3d(0, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rf * Vec3d::UnitX() - Vec3d(1, 0, 0)).norm(), 0.0, 1e-12);
}

}  // namespace facecap
