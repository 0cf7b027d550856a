#include "facecap/fit/frame_solver.hpp"

#include <limits>

#include "facecap/core/box_qp.hpp"

namespace facecap {

namespace {

// Levenberg-Marquardt over the frame block's columns [first, last): each
// damped Gauss-Newton step is solved exactly as a QP whose bounds keep the
// expression weights in [0, 1] (pose columns are unbounded), and accepted only
// when it lowers the energy.
BlockSolveReport levenberg_marquardt(const FrameEnergy& energy, FrameParameters& x, int first, int last,
                                     int max_iterations) {
  BlockSolveReport rep;
  const int size = last - first;
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  double cost = energy.linearize(x, r, j);
  rep.initial_cost = cost;
  double lambda = 1e-4;
  for (rep.iterations = 0; rep.iterations < max_iterations; ++rep.iterations) {
    const auto jb = j.middleCols(first, size);
    const Eigen::MatrixXd h = jb.transpose() * jb;
    Eigen::VectorXd g = jb.transpose() * r;
    Eigen::VectorXd lower(size), upper(size);
    for (int k = 0; k < size; ++k) {
      const int col = first + k;
      if (col >= frame_block::kExpression) {
        g[k] += energy.expression_l1();  // the L1 prior is linear on w >= 0
        lower[k] = -x.values[col];
        upper[k] = 1.0 - x.values[col];
      } else {
        lower[k] = -inf;
        upper[k] = inf;
      }
    }
    bool accepted = false;
    for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
      Eigen::MatrixXd damped = h;
      damped.diagonal() += lambda * h.diagonal().cwiseMax(1e-6);
      Eigen::VectorXd step = Eigen::VectorXd::Zero(size);
      solve_box_qp(damped, g, lower, upper, step);
      FrameParameters trial = x;
      for (int k = 0; k < size; ++k) trial.values[first + k] += step[k];
      const double trial_cost = energy.cost(trial);
      if (trial_cost < cost) {
        accepted = true;
        const double decrease = cost - trial_cost;
        x = trial;
        lambda = std::max(1e-8, lambda / 4.0);
        cost = energy.linearize(x, r, j);
        if (decrease < 1e-7 * (1.0 + cost)) {
          ++rep.iterations;
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

}  // namespace

BlockSolveReport solve_pose(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  return levenberg_marquardt(energy, x, 0, frame_block::kExpression, max_iterations);
}

BlockSolveReport solve_expression(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  return levenberg_marquardt(energy, x, frame_block::kExpression, static_cast<int>(x.values.size()), max_iterations);
}

BlockSolveReport solve_joint(const FrameEnergy& energy, FrameParameters& x, int max_iterations) {
  return levenberg_marquardt(energy, x, 0, static_cast<int>(x.values.size()), max_iterations);
}

}  // namespace facecap
