#include "facecap/swap/albedo_adaptation.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"
#include "swap/square_grid.hpp"

namespace facecap {

TEST(AlbedoAdaptation, BoundaryTakesTheTargetInteriorKeepsSourceGradients) {
  const int n = 12, count = (n + 1) * (n + 1);
  const auto tris = test::square_grid(n);
  const AlbedoAdaptation adapt(tris, count, std::vector<bool>(count, true));
  EXPECT_EQ(adapt.boundary_count(), 4 * n);
  Positions source(3, count), target(3, count);
  for (int v = 0; v < count; ++v) {
    const float x = float(v % (n + 1)) / n, y = float(v / (n + 1)) / n;
    source.col(v) = Vec3f(0.6f + 0.1f * std::sin(9 * x) * std::cos(7 * y), 0.4f, 0.3f);  // textured
    target.col(v) = Vec3f(0.3f, 0.2f + 0.1f * x, 0.25f);                                 // darker, a gradient
  }
  const Positions h = adapt.offset(source, target);
  const std::vector<bool> boundary = boundary_vertices(tris, count);
  for (int v = 0; v < count; ++v) {
    if (boundary[v]) {
      EXPECT_LT((source.col(v) + h.col(v) - target.col(v)).norm(), 1e-5f) << v;
    }
  }
  // h is harmonic: the target is linear and the source's red texture is
  // kept: adapted - source in red is the harmonic extension of (0.3 - source)
  // on the boundary; green equals the target's linear ramp exactly.
  for (int v = 0; v < count; ++v) {
    const float x = float(v % (n + 1)) / n;
    EXPECT_NEAR(source(1, v) + h(1, v), 0.2f + 0.1f * x, 1e-4f);
    EXPECT_NEAR(h(2, v), -0.05f, 1e-5f);
  }
}

TEST(AlbedoAdaptation, AConstantShiftIsReproducedEverywhere) {
  const int n = 8, count = (n + 1) * (n + 1);
  const auto tris = test::square_grid(n);
  Positions source = Positions::Random(3, count) * 0.1f + Positions::Constant(3, count, 0.5f);
  const Positions target = source + Positions::Constant(3, count, -0.2f);
  const Positions h = AlbedoAdaptation(tris, count, std::vector<bool>(count, true)).offset(source, target);
  EXPECT_LT((h - Positions::Constant(3, count, -0.2f)).cwiseAbs().maxCoeff(), 1e-4f);
}

TEST(AlbedoAdaptation, OutliersOnTheOutlineTakeTheMedian) {
  const int n = 10, count = (n + 1) * (n + 1);
  const auto tris = test::square_grid(n);
  const Positions source = Positions::Constant(3, count, 0.5f);
  Positions target = Positions::Constant(3, count, 0.4f);
  target.col(3) = Vec3f(1.0f, 1.0f, 1.0f);  // a white collar on the outline
  const Positions h = AlbedoAdaptation(tris, count, std::vector<bool>(count, true)).offset(source, target);
  EXPECT_LT((h - Positions::Constant(3, count, -0.1f)).cwiseAbs().maxCoeff(), 1e-4f);
}

// A swap keeps an adaptation while the target's known outline stays the
// same: what is known inside the outline does not change it.
TEST(AlbedoAdaptation, TheSameOutlineKnownIsTheSameAdaptation) {
  const int n = 6, count = (n + 1) * (n + 1);
  const auto tris = test::square_grid(n);
  std::vector<bool> known(count, true);
  known[0] = false;  // a corner of the outline unseen
  const AlbedoAdaptation adapt(tris, count, known);
  EXPECT_TRUE(adapt.fixes_the_same(known));
  std::vector<bool> inside_unseen = known;
  inside_unseen[(n + 1) * 3 + 3] = false;  // the middle vertex: not on the outline
  EXPECT_TRUE(adapt.fixes_the_same(inside_unseen));
  std::vector<bool> corner_seen = known;
  corner_seen[0] = true;
  EXPECT_FALSE(adapt.fixes_the_same(corner_seen));
  std::vector<bool> edge_unseen = known;
  edge_unseen[2] = false;  // on the bottom edge
  EXPECT_FALSE(adapt.fixes_the_same(edge_unseen));
  EXPECT_FALSE(adapt.fixes_the_same(std::vector<bool>(count - 1, true)));
  // And it gives what a fresh one from the other known set gives.
  const Positions source = Positions::Random(3, count), target = Positions::Random(3, count);
  EXPECT_EQ(adapt.offset(source, target), AlbedoAdaptation(tris, count, inside_unseen).offset(source, target));
}

TEST(AlbedoAdaptation, NothingSeenOnTheOutlineIsAnError) {
  const auto tris = test::square_grid(4);
  EXPECT_THROW(AlbedoAdaptation(tris, 25, std::vector<bool>(25, false)), Error);
}

}  // namespace facecap
