#include "facecap/core/mesh.hpp"

#include <gtest/gtest.h>

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

}  // namespace facecap
