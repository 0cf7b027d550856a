#pragma once
// Exact solver for small dense box-constrained quadratic programs:
//   minimise 1/2 x^T H x + g^T x  subject to  lower <= x <= upper,
// with H symmetric positive definite, by a primal active-set method: solve
// the equality-constrained problem on the free variables (Cholesky), step to
// the first bound that blocks, and release a bound variable whose gradient
// points into the box, until the KKT conditions hold. Terminates at the exact
// optimum in finitely many steps (at most a few times the size for our problems).
#include <Eigen/Core>

namespace facecap {

struct BoxQpResult {
  int iterations = 0;
  bool converged = false;
  double objective = 0.0;
};

// x: in = a starting point (clamped into the box), out = the minimiser.
BoxQpResult solve_box_qp(const Eigen::MatrixXd& hessian, const Eigen::VectorXd& gradient, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper, Eigen::VectorXd& x, int max_iterations = 500);

}  // namespace facecap
