#pragma once
// Joint solve of the identity weights and the focal length with every frame's
// pose and expression weights (§4.1: identity and focal from the first
// frames): Levenberg-Marquardt on all unknowns at once, each frame's block
// eliminated by a Schur complement (the reduced system has only identity +
// focal unknowns), and the weights' box 0 <= w <= 1 kept by a projected
// Newton step whose active set is the bound weights the gradient presses
// outward (Bertsekas 1982).
//
// Block coordinate descent between identity and frames was measured to crawl
// (energy still falling after 15 rounds), and Ceres with bound constraints
// needed 20-40 iterations of 20 ms per solve; this converges in about a tenth
// of a second for 30 frames.
#include <functional>
#include <memory>
#include <vector>

#include "facecap/fit/frame_energy.hpp"

namespace facecap {

struct IdentitySolverOptions {
  int max_iterations = 30;
  bool focal_free = true;
  // false: the identity is given (CoarseFitOptions::known_identity) and held;
  // the focal length and the frames move.
  bool identity_free = true;
  double focal_guess = 1000.0;
  double sigma_log_focal = 0.5;
  // Called every few iterations to re-choose the jaw correspondences.
  std::function<void(const std::vector<FrameParameters>&, const Eigen::VectorXd& identity, double focal)> refresh;
  int refresh_every = 5;
};

struct IdentitySolveReport {
  double initial_cost = 0;
  double final_cost = 0;
  int iterations = 0;
  // Identity directions the landmarks determine, each counted by its data
  // precision over its posterior precision (0..modes), at the last
  // linearisation: what identity_size.hpp needs.
  double effective_modes = 0;
  // Posterior covariance of the identity coefficients at the last
  // linearisation, the frames' poses, expressions and the focal length
  // marginalised (modes x modes; empty if it could not be formed). It is the
  // solve's own belief: calibrated when the landmark sigma matches the
  // detector's error (shape_uncertainty.hpp).
  Eigen::MatrixXd identity_covariance;
};

IdentitySolveReport solve_identity_joint(const std::vector<std::unique_ptr<FrameEnergy>>& energies,
                                         std::vector<FrameParameters>& frames, Eigen::VectorXd& identity, double& focal,
                                         const IdentitySolverOptions& options);

}  // namespace facecap
