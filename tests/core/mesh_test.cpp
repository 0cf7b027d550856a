#include "facecap/core/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace facecap {

namespace {

// A unit cube as 6 outward-facing quads (counter-clockwise seen from outside).
std::vector<Polygon> cube_quads() {
  const int q[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  std::vector<Polygon> out;
  for (const auto& f : q) {
    Polygon p;
    for (int k = 0; k < 4; ++k) p.v[k] = f[k];
    out.push_back(p);
  }
  return out;
}

Positions cube_positions() {
  Positions p(3, 8);
  // Corners: bottom 0..3, top 4..7.
  p << 0, 1, 1, 0, 0, 1, 1, 0,  //
      0, 0, 1, 1, 0, 0, 1, 1,   //
      0, 0, 0, 0, 1, 1, 1, 1;
  return p;
}

}  // namespace

TEST(Mesh, TriangulateSplitsQuadsAndKeepsTriangles) {
  std::vector<Polygon> polys = cube_quads();
  Polygon tri;
  tri.v = {0, 1, 2, -1};
  polys.push_back(tri);
  const TriangleMesh m = triangulate(polys, {}, 8);
  EXPECT_EQ(m.triangles.size(), 13u);
  EXPECT_TRUE(m.triangle_uvs.empty());
}

TEST(Mesh, AreaWeightedNormalsPointOutwardOnACube) {
  const TriangleMesh m = triangulate(cube_quads(), {}, 8);
  const Positions n = vertex_normals(cube_positions(), m.triangles);
  const Vec3f centre(0.5f, 0.5f, 0.5f);
  const Positions p = cube_positions();
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(n.col(i).norm(), 1.0f, 1e-5f);
    EXPECT_GT(n.col(i).dot(p.col(i) - centre), 0.5f) << "vertex " << i;
  }
}

TEST(Mesh, AdjacencyOfACubeVertexHasItsRing) {
  const TriangleMesh m = triangulate(cube_quads(), {}, 8);
  const VertexAdjacency adj = vertex_adjacency(m.triangles, 8);
  for (int i = 0; i < 8; ++i) {
    EXPECT_GE(adj.degree(i), 3);
    EXPECT_LE(adj.degree(i), 6);
  }
  EXPECT_EQ(adj.offsets.back(), static_cast<int>(adj.indices.size()));
}

TEST(Mesh, ClosedMeshHasNoBoundaryAndOpenOneHas) {
  const TriangleMesh closed = triangulate(cube_quads(), {}, 8);
  for (bool b : boundary_vertices(closed.triangles, 8)) EXPECT_FALSE(b);
  std::vector<Polygon> open = cube_quads();
  open.pop_back();
  const TriangleMesh m = triangulate(open, {}, 8);
  const auto boundary = boundary_vertices(m.triangles, 8);
  EXPECT_TRUE(boundary[0] && boundary[4] && boundary[7] && boundary[3]);
  EXPECT_FALSE(boundary[1] || boundary[2] || boundary[5] || boundary[6]);
}

TEST(Mesh, BoundaryLoopsGoRoundTheOutlineAndEachHole) {
  // A 6 x 6 grid of cells with two cells cut out, apart: the outline (24
  // edges) and two holes of 4 edges each.
  constexpr int n = 6;
  std::vector<Triangle> triangles;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if ((x == 1 && y == 1) || (x == 4 && y == 3)) continue;
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  const std::vector<std::vector<int>> loops = boundary_loops(triangles);
  ASSERT_EQ(loops.size(), 3u);
  EXPECT_EQ(loops[0].size(), 24u);
  EXPECT_EQ(loops[1].size(), 4u);
  EXPECT_EQ(loops[2].size(), 4u);
  // Each step of a loop is an edge that one triangle has, in its winding.
  auto has_edge = [&](int a, int b) {
    int count = 0;
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k) count += t[k] == a && t[(k + 1) % 3] == b;
    return count;
  };
  for (const std::vector<int>& loop : loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      EXPECT_EQ(has_edge(a, b), 1) << a << " -> " << b;
      EXPECT_EQ(has_edge(b, a), 0) << b << " -> " << a << " is inside";
    }
  // The holes are the cut cells' corners.
  std::vector<int> corners;
  for (const std::vector<int>& hole : {loops[1], loops[2]})
    for (const int v : hole) corners.push_back(v);
  std::sort(corners.begin(), corners.end());
  EXPECT_EQ(corners, (std::vector<int>{8, 9, 15, 16, 25, 26, 32, 33}));
  EXPECT_TRUE(boundary_loops(triangulate(cube_quads(), {}, 8).triangles).empty());
}

}  // namespace facecap
