#include "facecap/render/uv_bake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// A hexagonal fan of six triangles in the middle of the UV square, its
// vertices' UVs their positions, so that the islands have room to grow.
TriangleMesh hexagon() {
  TriangleMesh m;
  m.uvs.push_back({0.5f, 0.5f});
  for (int k = 0; k < 6; ++k) {
    const float a = float(k) * 3.14159265f / 3;
    m.uvs.push_back({0.5f + 0.3f * std::cos(a), 0.5f + 0.3f * std::sin(a)});
  }
  for (int k = 0; k < 6; ++k) m.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
  m.triangle_uvs = m.triangles;
  m.num_vertices = 7;
  return m;
}

// Two linear functions of UV, one of them negative over part of the mesh.
Eigen::MatrixXf linear_values(const TriangleMesh& m) {
  Eigen::MatrixXf v(2, m.num_vertices);
  for (int i = 0; i < m.num_vertices; ++i) {
    v(0, i) = 0.3f + 2.0f * m.uvs[i].x() - 1.5f * m.uvs[i].y();
    v(1, i) = -1.0f + m.uvs[i].y();
  }
  return v;
}

}  // namespace

// A linear function is what barycentric interpolation reproduces: every
// covered texel holds it at the UV of its centre as renderers read a
// texture (Blender, three.js, OpenGL: texel x at u = (x + 0.5) / N, row y
// at v = 1 - (y + 0.5) / N), channel by channel.
TEST(UvBaker, ACoveredTexelHoldsTheValueAtItsUv) {
  const TriangleMesh m = hexagon();
  constexpr int kSize = 64;
  const UvTexelMap map = rasterize_uv(m, kSize);
  const cv::Mat baked = UvBaker(m.triangles, map).bake(linear_values(m));
  ASSERT_EQ(baked.type(), CV_32FC2);
  int covered = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (map.triangle[map.index(x, y)] < 0) continue;
      ++covered;
      const float u = (float(x) + 0.5f) / kSize, v = 1.0f - (float(y) + 0.5f) / kSize;
      const cv::Vec2f b = baked.at<cv::Vec2f>(y, x);
      EXPECT_NEAR(b[0], 0.3f + 2.0f * u - 1.5f * v, 1e-4) << x << ',' << y;
      EXPECT_NEAR(b[1], -1.0f + v, 1e-4) << x << ',' << y;
    }
  EXPECT_GT(covered, 800);  // the hexagon's area, 0.234 of the square, is about 950 texels
}

// The grown border is a grey dilation by a 3 x 3 square a ring, over the
// covered texels only (negative values included), as OpenCV's would be with
// the uncovered texels at minus infinity; the rest stays 0.
TEST(UvBaker, TheIslandsGrowAsADilationOfTheCoveredTexels) {
  const TriangleMesh m = hexagon();
  constexpr int kSize = 48;
  const UvTexelMap map = rasterize_uv(m, kSize);
  const Eigen::MatrixXf values = linear_values(m);
  const cv::Mat baked = UvBaker(m.triangles, map, 2).bake(values);

  cv::Mat expected = UvBaker(m.triangles, map, 0).bake(values);
  cv::Mat covered(kSize, kSize, CV_8U, cv::Scalar(0));
  for (int i = 0; i < kSize * kSize; ++i) covered.data[i] = map.triangle[i] >= 0 ? 255 : 0;
  const int island = cv::countNonZero(covered);
  expected.setTo(cv::Scalar::all(std::numeric_limits<float>::lowest()), covered == 0);
  for (int ring = 0; ring < 2; ++ring) {
    cv::Mat grown, grown_cover;
    cv::dilate(expected, grown, cv::Mat());
    cv::dilate(covered, grown_cover, cv::Mat());
    grown.copyTo(expected, covered == 0);
    covered = grown_cover;
  }
  expected.setTo(cv::Scalar::all(0), covered == 0);
  EXPECT_EQ(cv::norm(baked, expected, cv::NORM_INF), 0.0);
  // The rings did grow: two rings round a hexagon 29 texels across.
  EXPECT_GT(cv::countNonZero(covered), island + 2 * 80);
}

TEST(UvBaker, RefusesMoreThanFourValuesAVertex) {
  const TriangleMesh m = hexagon();
  const UvBaker baker(m.triangles, rasterize_uv(m, 16));
  EXPECT_THROW(baker.bake(Eigen::MatrixXf::Zero(5, m.num_vertices)), Error);
}

}  // namespace facecap
