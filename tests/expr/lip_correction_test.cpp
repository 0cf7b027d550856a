#include "facecap/expr/lip_correction.hpp"

#include <gtest/gtest.h>

#include <random>

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

TEST(LipCorrection, KeepsTheKeyLipVerticesWithinBounds) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::MatrixXd rows = lip_basis(*model);
  const int n = static_cast<int>(model->expression_names.size());
  ASSERT_EQ(rows.rows(), 12);
  ASSERT_EQ(rows.cols(), n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 0.6f);
  double worst_before = 0, worst_after = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXf source(n), target(n);
    for (int k = 0; k < n; ++k) {
      source[k] = u(rng);
      target[k] = std::min(1.0f, source[k] + u(rng) * (k % 3 == 0));  // an expression change touching many shapes
    }
    const Eigen::VectorXf w = correct_lips(rows, target, source);
    EXPECT_GE(w.minCoeff(), 0.0f);
    EXPECT_LE(w.maxCoeff(), 1.0f);
    const Eigen::VectorXd before = rows * (target - source).cast<double>();
    const Eigen::VectorXd after = rows * (w - source).cast<double>();
    double b = 0, a = 0;
    for (int v = 0; v < 4; ++v) {
      b = std::max(b, before.segment<3>(3 * v).norm());
      a = std::max(a, after.segment<3>(3 * v).norm());
    }
    worst_before = std::max(worst_before, b);
    worst_after = std::max(worst_after, a);
  }
  // Positions in cm: the change moves the lips by millimetres; the corrected
  // weights leave them within 0.2 mm (alpha = 1000 trades a little).
  EXPECT_GT(worst_before, 0.1);
  EXPECT_LT(worst_after, 0.02);
}

TEST(LipCorrection, LeavesATargetThatKeepsTheLipsUntouched) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::MatrixXd rows = lip_basis(*model);
  const Eigen::VectorXf source = Eigen::VectorXf::Constant(rows.cols(), 0.2f);
  const Eigen::VectorXf w = correct_lips(rows, source, source);
  EXPECT_LT((w - source).cwiseAbs().maxCoeff(), 1e-5f);
}

}  // namespace facecap
