#include "facecap/render/uv_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace facecap {

namespace {

const PinholeCamera kCamera{300.0, 64.0, 48.0};

// A square [-1, 1]^2 tilted away from the camera (z = 12 + 2x, so that
// perspective matters), wound to face it, its UVs an affine function of its
// points: u = (x + 1) / 2, v = (y + 1) / 2.
struct TiltedSquare {
  TriangleMesh mesh;
  Positions points{3, 4};
  TiltedSquare() {
    points << -1, 1, 1, -1, -1, -1, 1, 1, 10, 14, 14, 10;
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    mesh.triangle_uvs = mesh.triangles;
    for (int i = 0; i < 4; ++i) mesh.uvs.push_back({(points(0, i) + 1) / 2, (points(1, i) + 1) / 2});
    mesh.num_vertices = 4;
  }
};

}  // namespace

// Each pixel holds the UV of the point its centre's ray meets (found here by
// intersecting the ray with the square's plane), to the 16-bit step; the
// pixels whose ray misses the square are empty, those that meet it opaque.
TEST(UvPass, EachPixelHoldsTheUvWhereItsRayMeetsTheSurface) {
  const TiltedSquare square;
  RasterBuffers buffers;
  const cv::Size size(128, 96);
  const cv::Mat pass = uv_pass(square.mesh, square.points, kCamera, size, buffers);
  ASSERT_EQ(pass.type(), CV_16UC4);
  ASSERT_EQ(pass.size(), size);
  int inside = 0;
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const double dx = (x - kCamera.cx) / kCamera.focal, dy = (y - kCamera.cy) / kCamera.focal;
      const double t = 12.0 / (1.0 - 2.0 * dx);  // the ray t (dx, dy, 1) on the plane z = 12 + 2x
      const double px = t * dx, py = t * dy;
      const cv::Vec<uint16_t, 4> p = pass.at<cv::Vec<uint16_t, 4>>(y, x);
      if (std::abs(px) > 1.02 || std::abs(py) > 1.02) {
        EXPECT_EQ(p, (cv::Vec<uint16_t, 4>(0, 0, 0, 0))) << x << ',' << y;
        continue;
      }
      if (std::abs(px) > 0.98 || std::abs(py) > 0.98) continue;  // the edge: either
      ++inside;
      ASSERT_EQ(p[3], 65535) << x << ',' << y;
      EXPECT_EQ(p[0], 0);
      EXPECT_NEAR(p[2] / 65535.0, (px + 1) / 2, 3e-5) << x << ',' << y;  // red: u
      EXPECT_NEAR(p[1] / 65535.0, (py + 1) / 2, 3e-5) << x << ',' << y;  // green: v
    }
  EXPECT_GT(inside, 1500);  // the square is some 50 px across
}

// A second pass with the buffers of the first is the same as a fresh one
// (the rasteriser clears only what it drew before).
TEST(UvPass, ReusedBuffersGiveTheSamePass) {
  const TiltedSquare square;
  Positions moved = square.points;
  moved.row(0).array() += 0.7f;
  RasterBuffers reused, fresh;
  uv_pass(square.mesh, square.points, kCamera, {128, 96}, reused);
  const cv::Mat again = uv_pass(square.mesh, moved, kCamera, {128, 96}, reused);
  const cv::Mat first = uv_pass(square.mesh, moved, kCamera, {128, 96}, fresh);
  EXPECT_EQ(cv::norm(again, first, cv::NORM_INF), 0.0);
}

}  // namespace facecap
