#include "facecap/core/midpoint_subdivision.hpp"

#include <gtest/gtest.h>

namespace facecap {

TEST(MidpointSubdivision, TwoTrianglesSubdivideToSharedMidpoints) {
  const std::vector<Triangle> tris{{0, 1, 2}, {0, 2, 3}};
  const MidpointSubdivision s = subdivide_midpoint(tris, 4, 1);
  EXPECT_EQ(s.triangles.size(), 8u);
  EXPECT_EQ(s.num_vertices, 4 + 5);  // 5 distinct edges, the diagonal shared
  const MidpointSubdivision s2 = subdivide_midpoint(tris, 4, 2);
  EXPECT_EQ(s2.triangles.size(), 32u);
}

TEST(MidpointSubdivision, ProlongAveragesParents) {
  const std::vector<Triangle> tris{{0, 1, 2}};
  const MidpointSubdivision s = subdivide_midpoint(tris, 3, 2);
  Positions p(3, 3);
  p << 0, 2, 0, 0, 0, 2, 1, 1, 1;
  const Positions f = s.prolong(p);
  ASSERT_EQ(f.cols(), s.num_vertices);
  for (int v = 0; v < f.cols(); ++v) {
    EXPECT_NEAR(f(2, v), 1.0f, 1e-6f);           // stays on the plane z = 1
    EXPECT_LE(f(0, v) + f(1, v), 2.0f + 1e-6f);  // stays inside the triangle
    EXPECT_GE(f(0, v), -1e-6f);
  }
}

}  // namespace facecap
