#include "facecap/io/nuke_chan.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace facecap {

// Angles about one axis come back as themselves, in their own column.
TEST(NukeChan, ARotationAboutOneAxisIsThatAngle) {
  const double degree = 3.14159265358979323846 / 180;
  const Vec3d about_y = euler_zxy_degrees(Eigen::AngleAxisd(30 * degree, Vec3d::UnitY()).toRotationMatrix());
  EXPECT_TRUE(about_y.isApprox(Vec3d(0, 30, 0), 1e-12)) << about_y.transpose();
  const Vec3d about_x = euler_zxy_degrees(Eigen::AngleAxisd(-20 * degree, Vec3d::UnitX()).toRotationMatrix());
  EXPECT_TRUE(about_x.isApprox(Vec3d(-20, 0, 0), 1e-12)) << about_x.transpose();
  const Vec3d about_z = euler_zxy_degrees(Eigen::AngleAxisd(170 * degree, Vec3d::UnitZ()).toRotationMatrix());
  EXPECT_TRUE(about_z.isApprox(Vec3d(0, 0, 170), 1e-12)) << about_z.transpose();
}

// Any rotation, and the order Nuke applies them in (z, then x, then y: the
// matrix Ry Rx Rz): the angles rebuild the rotation, rx within +-90 degrees,
// at gimbal lock too.
TEST(NukeChan, TheAnglesRebuildAnyRotationInNukesOrder) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 1000; ++i) {
    const Mat3d r =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
    const Vec3d angles = euler_zxy_degrees(r);
    EXPECT_LE(std::abs(angles.x()), 90.0);
    EXPECT_LT((rotation_from_euler_zxy_degrees(angles) - r).cwiseAbs().maxCoeff(), 1e-9) << i;
  }
  const double degree = 3.14159265358979323846 / 180;
  const Vec3d rz_first(0, 0, 25);  // z alone, then x, then y
  const Mat3d nuke = Eigen::AngleAxisd(40 * degree, Vec3d::UnitY()).toRotationMatrix() *
                     Eigen::AngleAxisd(-15 * degree, Vec3d::UnitX()).toRotationMatrix() *
                     Eigen::AngleAxisd(rz_first.z() * degree, Vec3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(euler_zxy_degrees(nuke).isApprox(Vec3d(-15, 40, 25), 1e-12));
  for (const double rx : {90.0, -90.0}) {  // gimbal lock: z folds into y
    const Mat3d locked = rotation_from_euler_zxy_degrees(Vec3d(rx, 35, 10));
    const Vec3d angles = euler_zxy_degrees(locked);
    EXPECT_NEAR(angles.x(), rx, 1e-6);
    EXPECT_LT((rotation_from_euler_zxy_degrees(angles) - locked).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(NukeChan, ALineIsFrameTranslationRotationAndForACameraItsFieldOfView) {
  EXPECT_EQ(chan_line(1, Vec3d(1.5, -2, 100.25), Vec3d(0, 30, -5)),
            "1 1.500000 -2.000000 100.250000 0.000000 30.000000 -5.000000\n");
  EXPECT_EQ(chan_line(12, Vec3d::Zero(), Vec3d::Zero(), 25.26114),
            "12 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 25.261140\n");
}

}  // namespace facecap
