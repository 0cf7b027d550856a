#include "facecap/core/edge_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// An n x n grid of unit squares, each split along its rising diagonal (from
// (x, y) to (x + 1, y + 1)); vertex x + (n + 1) y at (x, y, 0). One vertex
// more, at the end, in no triangle.
struct Grid {
  Positions positions;
  std::vector<Triangle> triangles;
  int at(int x, int y) const { return x + (n + 1) * y; }
  int n;
};

Grid grid(int n) {
  Grid g{Positions::Zero(3, (n + 1) * (n + 1) + 1), {}, n};
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) g.positions.col(g.at(x, y)) = Vec3f(float(x), float(y), 0);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      g.triangles.push_back({g.at(x, y), g.at(x + 1, y), g.at(x + 1, y + 1)});
      g.triangles.push_back({g.at(x, y), g.at(x + 1, y + 1), g.at(x, y + 1)});
    }
  return g;
}

}  // namespace

TEST(EdgeDistance, EachVertexGetsItsShortestPathAlongEdges) {
  const Grid g = grid(4);
  const auto adjacency = vertex_adjacency(g.triangles, int(g.positions.cols()));
  const std::vector<double> d = edge_path_distances(g.positions, adjacency, {g.at(0, 0)});
  EXPECT_DOUBLE_EQ(d[size_t(g.at(0, 0))], 0.0);
  EXPECT_NEAR(d[size_t(g.at(3, 0))], 3.0, 1e-6);                 // along a row
  EXPECT_NEAR(d[size_t(g.at(3, 3))], 3 * std::sqrt(2.0), 1e-6);  // along the diagonals
  EXPECT_NEAR(d[size_t(g.at(2, 1))], 1 + std::sqrt(2.0), 1e-6);  // one diagonal, one step
  // Against the split, a path must go round: two unit steps for (0, 1) to (1, 0).
  const std::vector<double> from_side = edge_path_distances(g.positions, adjacency, {g.at(0, 1)});
  EXPECT_NEAR(from_side[size_t(g.at(1, 0))], 2.0, 1e-6);
  EXPECT_TRUE(std::isinf(d.back()));  // in no triangle: no path reaches it
}

TEST(EdgeDistance, SeveralSourcesGiveTheDistanceToTheNearest) {
  const Grid g = grid(4);
  const auto adjacency = vertex_adjacency(g.triangles, int(g.positions.cols()));
  const std::vector<double> d = edge_path_distances(g.positions, adjacency, {g.at(0, 2), g.at(4, 2)});
  for (int x = 0; x <= 4; ++x) EXPECT_NEAR(d[size_t(g.at(x, 2))], std::min(x, 4 - x), 1e-6) << x;
  EXPECT_THROW(edge_path_distances(g.positions, adjacency, {int(g.positions.cols())}), Error);
}

}  // namespace facecap
