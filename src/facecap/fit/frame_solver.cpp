#include "facecap/fit/frame_solver.hpp"

#include <Eigen/Cholesky>
#include <limits>

#include "facecap/core/box_qp.hpp"

namespace facecap {

BlockSolveReport solve_pose(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  BlockSolveReport rep;
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  double lambda = 1e-3;
  double cost = energy.linearize(x, r, j);
  rep.initial_cost = cost;
  for (rep.iterations = 0; rep.iterations < max_iterations; ++rep.iterations) {
    const Eigen::Matrix<double, Eigen::Dynamic, 6> jp = j.leftCols<6>();
    const Eigen::Matrix<double, 6, 6> h = jp.transpose() * jp;
    const Eigen::Matrix<double, 6, 1> g = jp.transpose() * r;
    bool accepted = false;
    for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
      Eigen::Matrix<double, 6, 6> damped = h;
      damped.diagonal() += lambda * h.diagonal().cwiseMax(1e-9);
      const Eigen::Matrix<double, 6, 1> step = damped.ldlt().solve(-g);
      FrameParameters trial = x;
      for (int k = 0; k < 6; ++k) trial.values[k] += step[k];
      const double trial_cost = energy.cost(trial);
      if (trial_cost < cost) {
        accepted = true;
        const double decrease = cost - trial_cost;
        x = trial;
        lambda = std::max(1e-7, lambda / 3.0);
        cost = energy.linearize(x, r, j);
        if (decrease < 1e-7 * (1.0 + cost)) {
          rep.final_cost = cost;
          return rep;
        }
      } else {
        lambda *= 4.0;
      }
    }
    if (!accepted) break;
  }
  rep.final_cost = cost;
  return rep;
}

BlockSolveReport solve_expression(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  BlockSolveReport rep;
  const int n = x.num_expressions();
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  double cost = energy.linearize(x, r, j);
  rep.initial_cost = cost;
  for (rep.iterations = 0; rep.iterations < max_iterations; ++rep.iterations) {
    const auto jw = j.rightCols(n);
    const Eigen::MatrixXd h = jw.transpose() * jw;
    // The L1 sparsity prior is linear on w >= 0: it adds lambda to the gradient.
    const Eigen::VectorXd g = jw.transpose() * r + Eigen::VectorXd::Constant(n, energy.expression_l1());
    const Eigen::VectorXd w = x.expression();
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    // The Gauss-Newton model restricted to 0 <= w + step <= 1, solved exactly.
    solve_box_qp(h, g, -w, Eigen::VectorXd::Ones(n) - w, step);
    double trial_cost = cost;
    FrameParameters trial = x;
    for (int halving = 0; halving < 4; ++halving) {
      trial = x;
      trial.expression() = w + step;
      trial_cost = energy.cost(trial);
      if (trial_cost < cost) break;
      step *= 0.5;  // a box-feasible direction stays feasible when shortened
    }
    if (trial_cost >= cost) break;
    const double decrease = cost - trial_cost;
    x = trial;
    cost = energy.linearize(x, r, j);
    if (decrease < 1e-6 * (1.0 + cost)) {
      ++rep.iterations;
      break;
    }
  }
  rep.final_cost = cost;
  return rep;
}

BlockSolveReport solve_joint(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  BlockSolveReport rep;
  const int n = x.num_expressions();
  const int size = frame_block::kExpression + n;
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  double cost = energy.linearize(x, r, j);
  rep.initial_cost = cost;
  double lambda = 1e-4;
  const double inf = std::numeric_limits<double>::infinity();
  for (rep.iterations = 0; rep.iterations < max_iterations; ++rep.iterations) {
    const Eigen::MatrixXd h = j.transpose() * j;
    Eigen::VectorXd g = j.transpose() * r;
    g.tail(n).array() += energy.expression_l1();
    const Eigen::VectorXd w = x.expression();
    Eigen::VectorXd lower(size), upper(size);
    lower.head(frame_block::kExpression).setConstant(-inf);
    upper.head(frame_block::kExpression).setConstant(inf);
    lower.tail(n) = -w;
    upper.tail(n) = Eigen::VectorXd::Ones(n) - w;
    bool accepted = false;
    for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
      Eigen::MatrixXd damped = h;
      damped.diagonal() += lambda * h.diagonal().cwiseMax(1e-6);
      Eigen::VectorXd step = Eigen::VectorXd::Zero(size);
      solve_box_qp(damped, g, lower, upper, step);
      FrameParameters trial = x;
      for (int k = 0; k < size; ++k) trial.values[k] += step[k];
      const double trial_cost = energy.cost(trial);
      if (trial_cost < cost) {
        accepted = true;
        const double decrease = cost - trial_cost;
        x = trial;
        lambda = std::max(1e-8, lambda / 4.0);
        cost = energy.linearize(x, r, j);
        if (decrease < 1e-7 * (1.0 + cost)) {
          rep.final_cost = cost;
          return rep;
        }
      } else {
        lambda *= 8.0;
      }
    }
    if (!accepted) break;
  }
  rep.final_cost = cost;
  return rep;
}

}  // namespace facecap
