#include "facecap/core/box_qp.hpp"

#include <Eigen/Cholesky>
#include <limits>
#include <vector>

namespace facecap {

namespace {

enum class Bound : unsigned char { kFree, kLower, kUpper };

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& h, const Eigen::VectorXd& g, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper, Eigen::VectorXd& x, int max_iterations) {
  const int n = static_cast<int>(g.size());
  BoxQpResult result;
  std::vector<Bound> state(n, Bound::kFree);
  x = x.cwiseMax(lower).cwiseMin(upper);
  for (int i = 0; i < n; ++i) {
    if (x[i] <= lower[i])
      state[i] = Bound::kLower;
    else if (x[i] >= upper[i])
      state[i] = Bound::kUpper;
  }
  constexpr double kTol = 1e-12;
  std::vector<int> free_idx;
  for (result.iterations = 0; result.iterations < max_iterations; ++result.iterations) {
    free_idx.clear();
    for (int i = 0; i < n; ++i)
      if (state[i] == Bound::kFree) free_idx.push_back(i);
    const int nf = static_cast<int>(free_idx.size());
    if (nf > 0) {
      // Minimiser over the free variables with the others held at their bounds.
      Eigen::MatrixXd hff(nf, nf);
      Eigen::VectorXd rhs(nf);
      const Eigen::VectorXd grad = h * x + g;
      for (int a = 0; a < nf; ++a) {
        rhs[a] = -grad[free_idx[a]];
        for (int b = 0; b < nf; ++b) hff(a, b) = h(free_idx[a], free_idx[b]);
      }
      const Eigen::VectorXd step = hff.llt().solve(rhs);
      // Largest feasible fraction of the step.
      double alpha = 1.0;
      int blocking = -1;
      Bound blocking_bound = Bound::kFree;
      for (int a = 0; a < nf; ++a) {
        const int i = free_idx[a];
        const double s = step[a];
        if (s < -kTol && x[i] + s < lower[i]) {
          const double t = (lower[i] - x[i]) / s;
          if (t < alpha) alpha = t, blocking = i, blocking_bound = Bound::kLower;
        } else if (s > kTol && x[i] + s > upper[i]) {
          const double t = (upper[i] - x[i]) / s;
          if (t < alpha) alpha = t, blocking = i, blocking_bound = Bound::kUpper;
        }
      }
      for (int a = 0; a < nf; ++a) x[free_idx[a]] += std::max(0.0, alpha) * step[a];
      if (blocking >= 0) {
        state[blocking] = blocking_bound;
        x[blocking] = blocking_bound == Bound::kLower ? lower[blocking] : upper[blocking];
        continue;  // a bound became active: re-solve on the smaller free set
      }
    }
    // At the free-set optimum: release the bound with the most negative multiplier.
    const Eigen::VectorXd grad = h * x + g;
    int release = -1;
    double most = 1e-10;
    for (int i = 0; i < n; ++i) {
      const double pull = state[i] == Bound::kLower ? -grad[i] : state[i] == Bound::kUpper ? grad[i] : 0.0;
      if (pull > most) most = pull, release = i;
    }
    if (release < 0) {
      result.converged = true;
      break;
    }
    state[release] = Bound::kFree;
  }
  result.objective = 0.5 * x.dot(h * x) + g.dot(x);
  return result;
}

}  // namespace facecap
