#include "facecap/expr/lip_correction.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <utility>

#include "test_support.hpp"

namespace facecap {

TEST(WindowMean, WeighsFramesByConfidence) {
  const std::vector<Eigen::VectorXf> w = {Eigen::Vector2f(0, 1), Eigen::Vector2f(1, 1), Eigen::Vector2f(3, 0)};
  const Eigen::VectorXf m = window_mean(w, {1.0f, 2.0f, 1.0f});
  EXPECT_NEAR(m[0], (0 + 2 + 3) / 4.0f, 1e-6f);
  EXPECT_NEAR(m[1], (1 + 2 + 0) / 4.0f, 1e-6f);
  // A frame the discriminator rejects outright still counts a little, never divides by zero.
  const Eigen::VectorXf z = window_mean(w, {0.0f, 0.0f, 0.0f});
  EXPECT_TRUE(z.allFinite());
}

// eq. 5.4 trades the expression against the lips: the larger alpha, the
// nearer the four key lip vertices stay to the speaker's. 0 leaves the target
// as it is; the default (the paper's 1000 per FaceWarehouse unit^2, 10 per
// cm^2) takes most of the lips' movement away; 1000 per cm^2 pins them.
TEST(LipCorrection, HoldsTheKeyLipVerticesAsFirmlyAsAlphaSays) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::MatrixXd rows = lip_basis(*model);
  const int n = static_cast<int>(model->expression_names.size());
  ASSERT_EQ(rows.rows(), 12);
  ASSERT_EQ(rows.cols(), n);
  // The largest movement of a key lip vertex (cm) over 20 random expression
  // changes touching many shapes, before and after the correction.
  const auto worst_movement = [&](double alpha) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 0.6f);
    double before = 0, after = 0;
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXf source(n), target(n);
      for (int k = 0; k < n; ++k) {
        source[k] = u(rng);
        target[k] = std::min(1.0f, source[k] + u(rng) * (k % 3 == 0));
      }
      const Eigen::VectorXf w = correct_lips(rows, target, source, {.alpha = alpha});
      EXPECT_GE(w.minCoeff(), 0.0f);
      EXPECT_LE(w.maxCoeff(), 1.0f);
      const Eigen::VectorXd moved_before = rows * (target - source).cast<double>();
      const Eigen::VectorXd moved_after = rows * (w - source).cast<double>();
      for (int v = 0; v < 4; ++v) {
        before = std::max(before, moved_before.segment<3>(3 * v).norm());
        after = std::max(after, moved_after.segment<3>(3 * v).norm());
      }
    }
    return std::pair{before, after};
  };
  const auto [before, free_lips] = worst_movement(0.0);
  const auto [before_default, held] = worst_movement(LipCorrectionOptions{}.alpha);
  const auto [before_pinned, pinned] = worst_movement(1000.0);
  EXPECT_GT(before, 0.1);  // the change moves the lips by millimetres
  EXPECT_DOUBLE_EQ(before_default, before);
  EXPECT_DOUBLE_EQ(before_pinned, before);
  EXPECT_NEAR(free_lips, before, 1e-6);
  EXPECT_LT(held, 0.1);  // within the 1 mm, even for these changes of up to 14 mm
  EXPECT_GT(held, 4 * pinned);
  EXPECT_LT(pinned, 0.02);
  std::printf("worst key lip movement: %.3f mm unheld, %.3f mm at alpha %.0f, %.4f mm at 1000\n", 10 * before,
              10 * held, LipCorrectionOptions{}.alpha, 10 * pinned);
}

TEST(LipCorrection, LeavesATargetThatKeepsTheLipsUntouched) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::MatrixXd rows = lip_basis(*model);
  const Eigen::VectorXf source = Eigen::VectorXf::Constant(rows.cols(), 0.2f);
  const Eigen::VectorXf w = correct_lips(rows, source, source);
  EXPECT_LT((w - source).cwiseAbs().maxCoeff(), 1e-5f);
}

}  // namespace facecap
