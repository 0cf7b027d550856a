// The source face is brought to the target face's size, keeping its shape.
#include "facecap/swap/size_match.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

Positions random_shape(int n, int seed) {
  std::srand(seed);
  return Positions::Random(3, n) * 8.0f;
}

}  // namespace

TEST(SizeMatch, RecoversTheScaleAndCentreOfAScaledShiftedCopy) {
  const Positions target = random_shape(200, 3);
  // The source: the target 1.07 times larger, elsewhere.
  const Vec3f shift(2.0f, -1.0f, 5.0f);
  Positions source = target * 1.07f;
  source.colwise() += shift;
  const SizeMatch m = match_size(source, target);
  EXPECT_NEAR(m.scale, 1.0 / 1.07, 1e-5);
  const Positions matched = m.apply(source);
  EXPECT_LT((matched - target).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(SizeMatch, KeepsTheSourceShape) {
  // A different shape (the target with a centimetre of noise per point),
  // 1.2 times larger: the match moves it onto the target's centroid, and the
  // distances between its points change by the one scale factor.
  const Positions target = random_shape(100, 5);
  const Positions source = (target + random_shape(100, 6) / 8.0f) * 1.2f;
  const SizeMatch m = match_size(source, target);
  const Positions matched = m.apply(source);
  const double before = (source.col(0) - source.col(1)).norm(), after = (matched.col(0) - matched.col(1)).norm();
  EXPECT_NEAR(m.scale, 1 / 1.2, 0.02);
  EXPECT_NEAR(after / before, m.scale, 1e-5);
  EXPECT_LT((matched.rowwise().mean() - target.rowwise().mean()).norm(), 1e-4);
}

TEST(SizeMatch, MismatchedShapesAreAnError) {
  EXPECT_THROW(match_size(Positions::Zero(3, 4), Positions::Zero(3, 5)), Error);
  EXPECT_THROW(match_size(Positions(3, 0), Positions(3, 0)), Error);
}

}  // namespace facecap
