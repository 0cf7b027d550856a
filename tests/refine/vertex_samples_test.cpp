// Observations next to unobserved vertices are dropped ring by ring.
#include "facecap/refine/vertex_samples.hpp"

#include <gtest/gtest.h>

namespace facecap {

namespace {

// A 9 x 9 vertex grid, two triangles per cell.
std::vector<Triangle> grid_triangles(int n) {
  std::vector<Triangle> t;
  for (int y = 0; y + 1 < n; ++y) {
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x;
      t.push_back({a, a + 1, a + n + 1});
      t.push_back({a, a + n + 1, a + n});
    }
  }
  return t;
}

int grid_distance(int a, int b, int n) {
  // Steps on this triangulation: x and y moves, and diagonal (+1, +1) moves.
  const int dx = a % n - b % n, dy = a / n - b / n;
  return (dx > 0) == (dy > 0) ? std::max(std::abs(dx), std::abs(dy)) : std::abs(dx) + std::abs(dy);
}

}  // namespace

TEST(ErodeObservations, DropsTheRingsAroundAnUnobservedVertex) {
  const int n = 9;
  const VertexAdjacency rings = vertex_adjacency(grid_triangles(n), n * n);
  const int hole = 4 * n + 4;
  for (int depth = 0; depth <= 2; ++depth) {
    VertexSamples s;
    s.visible.assign(n * n, true);
    s.visible[hole] = false;
    erode_observations(s, rings, depth);
    int expected = 0;
    for (int v = 0; v < n * n; ++v) {
      const bool kept = grid_distance(v, hole, n) > depth;
      EXPECT_EQ(s.visible[v], kept) << "vertex " << v << " at depth " << depth;
      expected += kept;
    }
    EXPECT_EQ(s.visible_count, expected);
  }
}

TEST(ErodeObservations, AFullyObservedMeshKeepsEverything) {
  const int n = 5;
  const VertexAdjacency rings = vertex_adjacency(grid_triangles(n), n * n);
  VertexSamples s;
  s.visible.assign(n * n, true);
  erode_observations(s, rings, 3);
  EXPECT_EQ(s.visible_count, n * n);
}

}  // namespace facecap
