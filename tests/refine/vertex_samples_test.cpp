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

TEST(ErodeObservations, DropsTheRingsAroundAHoleInTheMesh) {
  // A 9 x 9 grid with the four cells around the centre vertex cut out: a hole
  // with no vertex in it (as the eyes and the mouth are), every vertex observed.
  const int n = 9;
  const int centre = 4 * n + 4;
  std::vector<Triangle> triangles;
  for (const Triangle& t : grid_triangles(n)) {
    const bool touches_centre = t[0] == centre || t[1] == centre || t[2] == centre;
    if (!touches_centre) triangles.push_back(t);
  }
  const VertexAdjacency rings = vertex_adjacency(triangles, n * n);
  std::vector<bool> open_boundary = boundary_vertices(triangles, n * n);
  // Only the hole's rim: the grid's outer edge stands for skin that goes on.
  for (int v = 0; v < n * n; ++v) {
    const int x = v % n, y = v / n;
    if (x == 0 || y == 0 || x == n - 1 || y == n - 1) open_boundary[v] = false;
  }
  for (int depth = 0; depth <= 2; ++depth) {
    VertexSamples s;
    s.visible.assign(n * n, true);
    s.visible[centre] = false;  // in no triangle: nothing to observe
    erode_observations(s, rings, depth, open_boundary);
    for (int v = 0; v < n * n; ++v) {
      if (v == centre) continue;
      int from_hole = n * n;  // the rim (the centre's old one-ring) is at 1
      for (int r = 0; r < n * n; ++r)
        if (grid_distance(r, centre, n) == 1) from_hole = std::min(from_hole, 1 + grid_distance(v, r, n));
      EXPECT_EQ(s.visible[v], from_hole > depth) << "vertex " << v << " at depth " << depth;
    }
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

// The solve's free set: the seen vertices and their rings, ring by ring.
TEST(GrowByRings, AddsTheRingsAroundAVertex) {
  const int n = 9;
  const VertexAdjacency rings = vertex_adjacency(grid_triangles(n), n * n);
  const int seed = 4 * n + 4;
  std::vector<bool> mask(n * n, false);
  mask[seed] = true;
  for (int depth = 0; depth <= 3; ++depth) {
    const std::vector<bool> grown = grow_by_rings(mask, rings, depth);
    for (int i = 0; i < n * n; ++i) EXPECT_EQ(grown[i], grid_distance(i, seed, n) <= depth) << "vertex " << i;
  }
  // Nothing grows from nothing, and a full mask stays full.
  EXPECT_EQ(grow_by_rings(std::vector<bool>(n * n, false), rings, 2), std::vector<bool>(n * n, false));
  EXPECT_EQ(grow_by_rings(std::vector<bool>(n * n, true), rings, 2), std::vector<bool>(n * n, true));
}

}  // namespace facecap
