#include "facecap/core/statistics.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace facecap {

TEST(PearsonCorrelation, LinearRelationsGivePlusOrMinusOne) {
  const std::vector<double> a{1, 2, 3, 4, 5};
  EXPECT_NEAR(pearson_correlation(a, {3, 5, 7, 9, 11}), 1.0, 1e-12);
  EXPECT_NEAR(pearson_correlation(a, {10, 8, 6, 4, 2}), -1.0, 1e-12);
}

TEST(PearsonCorrelation, MatchesAWorkedExample) {
  // Sums of products of deviations: cov 4, a 10, b 5.2.
  EXPECT_NEAR(pearson_correlation({1, 2, 3, 4, 5}, {2, 1, 4, 3, 3}), 4.0 / std::sqrt(10.0 * 5.2), 1e-12);
}

TEST(PearsonCorrelation, AConstantOrEmptySampleGivesZero) {
  EXPECT_EQ(pearson_correlation({1, 2, 3}, {4, 4, 4}), 0.0);
  EXPECT_EQ(pearson_correlation({}, {}), 0.0);
}

TEST(StandardDeviation, IsTheSamplesSpreadAboutItsMean) {
  EXPECT_DOUBLE_EQ(standard_deviation({2, 4, 4, 4, 5, 5, 7, 9}), 2.0);  // mean 5, squares summing to 32 over 8
  EXPECT_DOUBLE_EQ(standard_deviation({3, 3, 3}), 0.0);
  EXPECT_DOUBLE_EQ(standard_deviation({}), 0.0);
}

TEST(Median, TakesTheUpperMiddleOfAnEvenCountCopiedOrInPlace) {
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_EQ(median({}), 0.0);
  std::vector<float> odd{3, 1, 2}, even{4, 1, 3, 2};
  EXPECT_EQ(median_in_place(odd), 2.0f);
  EXPECT_EQ(median_in_place(even), 3.0f);
}

TEST(Quantile, PicksTheValueThatShareOfTheWayUpWithoutInterpolating) {
  std::vector<float> v{5, 1, 4, 2, 3, 9, 8, 7, 6, 10, 11};  // 1..11
  EXPECT_EQ(quantile(v, 0.0f), 1.0f);
  EXPECT_EQ(quantile(v, 0.5f), 6.0f);
  EXPECT_EQ(quantile(v, 0.1f), 2.0f);
  EXPECT_EQ(quantile(v, 0.95f), 10.0f);  // 9.5 places up, rounded down
  EXPECT_EQ(quantile(v, 1.0f), 11.0f);
}

}  // namespace facecap
