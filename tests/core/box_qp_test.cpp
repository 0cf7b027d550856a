#include "facecap/core/box_qp.hpp"

#include <Eigen/Cholesky>

#include <gtest/gtest.h>

#include <random>

namespace facecap {

namespace {

// KKT conditions of min 1/2 x'Hx + g'x on [l, u]: the gradient vanishes on
// free variables and points into the box at active bounds.
void expect_kkt(const Eigen::MatrixXd& h, const Eigen::VectorXd& g, const Eigen::VectorXd& l, const Eigen::VectorXd& u,
                const Eigen::VectorXd& x) {
  const Eigen::VectorXd grad = h * x + g;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    ASSERT_GE(x[i], l[i] - 1e-12);
    ASSERT_LE(x[i], u[i] + 1e-12);
    if (x[i] > l[i] + 1e-9 && x[i] < u[i] - 1e-9) {
      EXPECT_NEAR(grad[i], 0.0, 1e-7) << "free variable " << i;
    } else if (x[i] <= l[i] + 1e-9) {
      EXPECT_GE(grad[i], -1e-7) << "lower bound " << i;
    } else {
      EXPECT_LE(grad[i], 1e-7) << "upper bound " << i;
    }
  }
}

}  // namespace

TEST(BoxQp, UnconstrainedMinimumInsideTheBoxIsTheNewtonPoint) {
  Eigen::MatrixXd h(2, 2);
  h << 2, 0.5, 0.5, 1;
  const Eigen::VectorXd g = Eigen::Vector2d(-1, -0.5);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  const auto r = solve_box_qp(h, g, Eigen::Vector2d(-10, -10), Eigen::Vector2d(10, 10), x);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((x - h.ldlt().solve(-g)).norm(), 1e-12);
}

TEST(BoxQp, SatisfiesKktOnRandomIllConditionedProblems) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const int dim = 53;
    Eigen::MatrixXd a(80, dim);
    for (int i = 0; i < a.size(); ++i) a.data()[i] = n(rng);
    a.col(1) = a.col(0) + 1e-3 * a.col(2);  // nearly collinear columns, like blendshapes
    Eigen::MatrixXd h = a.transpose() * a + 1e-4 * Eigen::MatrixXd::Identity(dim, dim);
    Eigen::VectorXd g(dim);
    for (int i = 0; i < dim; ++i) g[i] = 10 * n(rng);
    Eigen::VectorXd x = Eigen::VectorXd::Constant(dim, 0.5);
    const auto r = solve_box_qp(h, g, Eigen::VectorXd::Zero(dim), Eigen::VectorXd::Ones(dim), x);
    ASSERT_TRUE(r.converged) << "trial " << trial;
    expect_kkt(h, g, Eigen::VectorXd::Zero(dim), Eigen::VectorXd::Ones(dim), x);
  }
}

TEST(BoxQp, MatchesBruteForceInTwoDimensions) {
  Eigen::MatrixXd h(2, 2);
  h << 1, 0.9, 0.9, 1;
  const Eigen::VectorXd g = Eigen::Vector2d(0.3, -2.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  solve_box_qp(h, g, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), x);
  double best = 1e9;
  Eigen::Vector2d best_x;
  for (int i = 0; i <= 1000; ++i) {
    for (int j = 0; j <= 1000; ++j) {
      const Eigen::Vector2d y(i / 1000.0, j / 1000.0);
      const double f = 0.5 * y.dot(h * y) + g.dot(y);
      if (f < best) best = f, best_x = y;
    }
  }
  EXPECT_LT((x - best_x).norm(), 2e-3);
}

}  // namespace facecap
