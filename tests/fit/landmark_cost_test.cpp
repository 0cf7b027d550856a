#include "facecap/fit/landmark_cost.hpp"

#include <gtest/gtest.h>

#include "facecap/fit/frame_block.hpp"

namespace facecap {

// Central differences against the analytic Jacobians of every block. (Ceres'
// GradientChecker would do the same, but its result type holds Eigen
// matrices whose layout differs between Debian's Ceres and our -march=native
// build.)
TEST(LandmarkCost, AnalyticJacobianMatchesNumericDifferentiation) {
  LandmarkTerm term;
  term.neutral = Eigen::Vector3d(1.0, -2.0, 9.0);
  term.identity_rows = Eigen::MatrixXd::Random(3, 5);
  term.expression_rows = Eigen::MatrixXd::Random(3, 7);
  term.observed = Eigen::Vector2d(300, 260);
  term.principal_point = Eigen::Vector2d(320, 240);
  term.inv_sigma = 0.5;
  const LandmarkCost cost(&term, 5, 7);
  const std::vector<int> sizes{6, 7, 5, 1};
  for (const Eigen::Vector3d& rotation : {Eigen::Vector3d(0.2, -0.3, 0.1), Eigen::Vector3d(0, 0, 0)}) {
    std::vector<std::vector<double>> blocks{{rotation.x(), rotation.y(), rotation.z(), 1.0, -0.5, 60.0},
                                            {0.1, 0.5, 0.0, 0.9, 0.3, 0.2, 0.7},
                                            {0.3, -1.2, 0.5, 0.0, 2.0},
                                            {800.0}};
    std::vector<std::vector<double>> analytic(4);
    std::vector<double*> jac(4);
    for (int b = 0; b < 4; ++b) {
      analytic[b].resize(2 * sizes[b]);
      jac[b] = analytic[b].data();
    }
    auto evaluate = [&](double* r, double** j) {
      const double* params[4] = {blocks[0].data(), blocks[1].data(), blocks[2].data(), blocks[3].data()};
      return cost.Evaluate(params, r, j);
    };
    double r0[2];
    ASSERT_TRUE(evaluate(r0, jac.data()));
    for (int b = 0; b < 4; ++b) {
      for (int k = 0; k < sizes[b]; ++k) {
        const double h = 1e-6 * std::max(1.0, std::abs(blocks[b][k]));
        double rp[2], rm[2];
        const double saved = blocks[b][k];
        blocks[b][k] = saved + h;
        evaluate(rp, nullptr);
        blocks[b][k] = saved - h;
        evaluate(rm, nullptr);
        blocks[b][k] = saved;
        for (int row = 0; row < 2; ++row) {
          const double numeric = (rp[row] - rm[row]) / (2 * h);
          const double a = analytic[b][row * sizes[b] + k];
          EXPECT_NEAR(a, numeric, 1e-5 * std::max(1.0, std::abs(numeric))) << "block " << b << " col " << k;
        }
      }
    }
  }
}

TEST(LandmarkCost, ResidualIsTheScaledReprojectionError) {
  LandmarkTerm term;
  term.neutral = Eigen::Vector3d(2.0, 1.0, 10.0);  // model space: F flips y and z
  term.identity_rows = Eigen::MatrixXd::Zero(3, 1);
  term.expression_rows = Eigen::MatrixXd::Zero(3, 1);
  term.observed = Eigen::Vector2d(100, 100);
  term.principal_point = Eigen::Vector2d(320, 240);
  term.inv_sigma = 0.5;
  const LandmarkCost cost(&term, 1, 1);
  std::vector<double> pose{0, 0, 0, 0, 0, 60};
  double w = 0, a = 0, focal = 500;
  const double* params[4] = {pose.data(), &w, &a, &focal};
  double r[2];
  ASSERT_TRUE(cost.Evaluate(params, r, nullptr));
  // Camera point (2, -1, 50): projection (320 + 500 * 0.04, 240 - 500 * 0.02) = (340, 230).
  EXPECT_NEAR(r[0], 0.5 * (340 - 100), 1e-9);
  EXPECT_NEAR(r[1], 0.5 * (230 - 100), 1e-9);
}

}  // namespace facecap
