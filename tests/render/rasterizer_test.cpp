#include "facecap/render/rasterizer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace facecap {

namespace {

const PinholeCamera kCamera{100.0, 50.0, 50.0};

// Square [-1, 1]^2 at depth z, wound to face the camera.
void square(Positions& p, std::vector<Triangle>& t, float z, int offset = 0) {
  Positions q(3, 4);
  q << -1, 1, 1, -1, -1, -1, 1, 1, z, z, z, z;
  const int n = static_cast<int>(p.cols());
  p.conservativeResize(3, n + 4);
  p.rightCols(4) = q;
  t.push_back({n + 0, n + 2, n + 1});
  t.push_back({n + 0, n + 3, n + 2});
  (void)offset;
}

}  // namespace

TEST(Rasterizer, CoversTheProjectedSquareAtItsDepth) {
  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 10.0f);
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(p, t, kCamera, b);
  int covered = 0;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      if (!b.covered(x, y)) continue;
      ++covered;
      EXPECT_NEAR(b.depth[y * 100 + x], 10.0f, 1e-4f);
      EXPECT_TRUE(x >= 40 && x <= 60 && y >= 40 && y <= 60);
    }
  }
  EXPECT_EQ(covered, 21 * 21);  // pixel centres on [40, 60] inclusive
}

TEST(Rasterizer, BackFacesAreCulled) {
  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 10.0f);
  for (auto& tri : t) std::swap(tri[1], tri[2]);
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(p, t, kCamera, b);
  EXPECT_EQ(std::count(b.triangle.begin(), b.triangle.end(), -1), 100 * 100);
  rasterize(p, t, kCamera, b, {.cull_back_faces = false});
  EXPECT_LT(std::count(b.triangle.begin(), b.triangle.end(), -1), 100 * 100);
}

TEST(Rasterizer, NearerSurfaceWinsAndBarycentricsArePerspectiveCorrect) {
  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 20.0f);
  // A slanted triangle in front: z from 8 to 12 across x.
  const int n = static_cast<int>(p.cols());
  p.conservativeResize(3, n + 3);
  p.col(n) = Vec3f(-1, -1, 8);
  p.col(n + 1) = Vec3f(1, -1, 12);
  p.col(n + 2) = Vec3f(-1, 1, 8);
  t.push_back({n, n + 2, n + 1});
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(p, t, kCamera, b);
  // Pixel (50, 45): ray (0, -0.05, 1) hits the slanted plane z = 10 + 2x where x = 0 -> z = 10.
  const size_t i = 45 * 100 + 50;
  ASSERT_EQ(b.triangle[i], 2);
  EXPECT_NEAR(b.depth[i], 10.0f, 1e-3f);
  const Triangle& tri = t[2];
  const Vec2f w = b.bary[i];
  const Vec3f point = (1 - w.x() - w.y()) * p.col(tri[0]) + w.x() * p.col(tri[1]) + w.y() * p.col(tri[2]);
  EXPECT_NEAR(point.x(), 0.0f, 1e-3f);
  EXPECT_NEAR(point.y(), -0.5f, 1e-3f);
  EXPECT_NEAR(point.z(), 10.0f, 1e-3f);
}

TEST(Rasterizer, OccludedVerticesAreNotVisible) {
  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 10.0f);
  Positions pts(3, 2);
  pts.col(0) = Vec3f(0.2f, 0.2f, 10.0f);  // on the square
  pts.col(1) = Vec3f(0.4f, 0.4f, 20.0f);  // behind it
  Positions normals(3, 2);
  normals.col(0) = Vec3f(0, 0, -1);
  normals.col(1) = Vec3f(0, 0, -1);
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(p, t, kCamera, b);
  const auto vis = vertex_visibility(pts, normals, kCamera, b);
  EXPECT_TRUE(vis[0]);
  EXPECT_FALSE(vis[1]);
  normals.col(0) = Vec3f(0, 0, 1);  // facing away
  EXPECT_FALSE(vertex_visibility(pts, normals, kCamera, b)[0]);
}

TEST(Rasterizer, VerticesOnASteepSlopeAreVisibleAndThoseBehindItAreNot) {
  // A plane turned 70 degrees away from the camera, meshed finer than the
  // pixels (as a refinement level is): at 0.1 cm per pixel its depth changes
  // 0.27 cm per pixel, more than the tolerance a flat surface needs.
  const float a = 70.0f * 3.14159265f / 180.0f;
  constexpr int kSide = 41;
  Positions p(3, kSide * kSide + 1);
  std::vector<Triangle> t;
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      const float u = -1.0f + 2.0f * i / (kSide - 1), v = -1.0f + 2.0f * j / (kSide - 1);
      p.col(j * kSide + i) = Vec3f(u * std::cos(a), v, 10.0f + u * std::sin(a));
      if (i + 1 < kSide && j + 1 < kSide) {
        const int k = j * kSide + i;
        t.push_back({k, k + 1, k + kSide + 1});
        t.push_back({k, k + kSide + 1, k + kSide});
      }
    }
  }
  p.col(kSide * kSide) = Vec3f(0.0f, 0.0f, 11.0f);  // 1 cm behind the plane's centre
  Positions normals(3, p.cols());
  normals.colwise() = Vec3f(std::sin(a), 0.0f, -std::cos(a));
  RasterBuffers b;
  b.resize(100, 100);
  RasterOptions no_culling;
  no_culling.cull_back_faces = false;
  rasterize(p, t, kCamera, b, no_culling);
  const auto vis = vertex_visibility(p, normals, kCamera, b, 0.1f);
  int seen = 0;
  for (int k = 0; k < kSide * kSide; ++k) seen += vis[k];
  EXPECT_EQ(seen, kSide * kSide);
  EXPECT_FALSE(vis[kSide * kSide]);
}

// Buffers are reused across frames: a second call leaves no trace of the
// first. The first call's triangle is larger than the image (it reaches past
// every band of rows) and covers every pixel at its depth.
TEST(Rasterizer, ReusedBuffersHoldOnlyTheLatestCall) {
  Positions big(3, 3);
  big << -2, 4, -2, -2, -2, 4, 1.5f, 1.5f, 1.5f;  // projects to (-83, -83), (317, -83), (-83, 317)
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(big, {{0, 1, 2}}, kCamera, b, {.cull_back_faces = false});
  EXPECT_EQ(std::count(b.triangle.begin(), b.triangle.end(), -1), 0);
  for (float z : b.depth) ASSERT_NEAR(z, 1.5f, 1e-4f);

  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 10.0f);
  rasterize(p, t, kCamera, b);
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      if (x >= 40 && x <= 60 && y >= 40 && y <= 60) continue;
      ASSERT_FALSE(b.covered(x, y)) << x << "," << y;
      ASSERT_TRUE(std::isinf(b.depth[y * 100 + x])) << x << "," << y;
    }
  }

  rasterize(p, {}, kCamera, b);
  EXPECT_EQ(std::count(b.triangle.begin(), b.triangle.end(), -1), 100 * 100);
}

// A buffer reused for a face that moves (rasterize() clears only the box
// the last call drew in) holds what fresh buffers would, pixel for pixel:
// triangles moving across the image, partly off it, then none.
TEST(Rasterizer, ReusedBuffersMatchFreshOnesAsTheDrawingMoves) {
  RasterBuffers reused;
  reused.resize(120, 90);
  for (int step = 0; step < 12; ++step) {
    Positions p(3, 6);
    const float dx = -1.6f + 0.35f * float(step), dy = 0.9f - 0.2f * float(step);
    p << dx - 1, dx + 1, dx, dx + 0.5f, dx + 2.5f, dx + 1.5f,     //
        dy - 1, dy - 1, dy + 1, dy - 0.2f, dy - 0.2f, dy + 1.8f,  //
        8, 8, 8, 7, 9, 8;
    const std::vector<Triangle> t = step == 11 ? std::vector<Triangle>{} : std::vector<Triangle>{{0, 2, 1}, {3, 5, 4}};
    RasterBuffers fresh;
    fresh.resize(120, 90);
    rasterize(p, t, kCamera, fresh, {.cull_back_faces = false});
    rasterize(p, t, kCamera, reused, {.cull_back_faces = false});
    ASSERT_EQ(reused.triangle, fresh.triangle) << "step " << step;
    for (size_t i = 0; i < fresh.depth.size(); ++i) {
      ASSERT_EQ(reused.depth[i], fresh.depth[i]) << "step " << step << ", pixel " << i;
      if (fresh.triangle[i] >= 0) {
        ASSERT_EQ(reused.bary[i], fresh.bary[i]) << "step " << step << ", pixel " << i;
      }
    }
  }
}

// Two triangles sharing an edge cover every pixel on it: a square that fills
// the image leaves no pixel of its diagonal uncovered (7 of them were, before
// the edge functions were evaluated in a canonical order).
TEST(Rasterizer, SharedEdgesLeaveNoCracks) {
  Positions p(3, 0);
  std::vector<Triangle> t;
  square(p, t, 1.5f);  // [-1, 1] at z 1.5 spans [-16.7, 116.7] px
  RasterBuffers b;
  b.resize(100, 100);
  rasterize(p, t, kCamera, b);
  EXPECT_EQ(std::count(b.triangle.begin(), b.triangle.end(), -1), 0);
  for (float z : b.depth) ASSERT_NEAR(z, 1.5f, 1e-4f);
}

// A jittered grid of small triangles (shared edges at every angle, as a
// face mesh's are) over the whole image, against each pixel's triangle
// found in double precision: every pixel drawn, by the triangle that holds
// it (where it is not within a hair of an edge), with its barycentrics.
TEST(Rasterizer, AJitteredMeshIsDrawnAsExactGeometrySaysPixelByPixel) {
  constexpr int kGrid = 41;  // vertices a side, some 3 px apart on a 100 px image
  const float z = 2.0f;      // the image spans [-1, 1] cm at this depth
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  Positions p(3, kGrid * kGrid);
  const float step = 2.6f / float(kGrid - 1);  // [-1.3, 1.3] cm: past the image's edges
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const bool border = i == 0 || j == 0 || i == kGrid - 1 || j == kGrid - 1;
      const float dx = border ? 0.0f : jitter(rng) * step, dy = border ? 0.0f : jitter(rng) * step;
      p.col(j * kGrid + i) = Vec3f(-1.3f + i * step + dx, -1.3f + j * step + dy, z);
    }
  std::vector<Triangle> t;
  for (int j = 0; j + 1 < kGrid; ++j)
    for (int i = 0; i + 1 < kGrid; ++i) {
      const int a = j * kGrid + i, b = a + 1, c = a + kGrid, d = c + 1;
      // Facing the camera (as square() winds them), the diagonal alternating.
      if ((i + j) % 2 == 0) {
        t.push_back({a, d, b});
        t.push_back({a, c, d});
      } else {
        t.push_back({a, c, b});
        t.push_back({b, c, d});
      }
    }
  RasterBuffers buffers;
  buffers.resize(100, 100);
  rasterize(p, t, kCamera, buffers);

  std::vector<std::array<Vec2f, 3>> screen(t.size());
  for (size_t k = 0; k < t.size(); ++k)
    for (int c = 0; c < 3; ++c) screen[k][c] = kCamera.project(Vec3f(p.col(t[k][c])));
  int checked = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const size_t i = size_t(y) * 100 + x;
      ASSERT_GE(buffers.triangle[i], 0) << "a crack at " << x << ", " << y;
      ASSERT_NEAR(buffers.depth[i], z, 1e-4f);
      for (size_t k = 0; k < t.size(); ++k) {
        const auto& q = screen[k];
        const auto edge = [&](int u, int v) {
          return (double(q[u].x()) - x) * (double(q[v].y()) - y) - (double(q[u].y()) - y) * (double(q[v].x()) - x);
        };
        const double area = edge(0, 1) + edge(1, 2) + edge(2, 0);
        const double w0 = edge(1, 2) / area, w1 = edge(2, 0) / area, w2 = edge(0, 1) / area;
        constexpr double kHair = 1e-4;
        if (w0 < kHair || w1 < kHair || w2 < kHair) continue;  // outside, or too near an edge to call
        EXPECT_EQ(buffers.triangle[i], int(k)) << "at " << x << ", " << y;
        EXPECT_NEAR(buffers.bary[i].x(), w1, 1e-4);  // flat: perspective-correct is linear
        EXPECT_NEAR(buffers.bary[i].y(), w2, 1e-4);
        ++checked;
      }
    }
  EXPECT_GT(checked, 9900);  // all but the pixels on an edge
}

}  // namespace facecap
