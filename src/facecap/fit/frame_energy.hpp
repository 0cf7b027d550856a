#pragma once
// One frame's coarse-fit energy (eq. 4.3) as stacked residuals: the 68
// landmark terms (eq. 4.4, Huber-robust), the expression prior (eq. 4.5) and,
// when a previous frame is given, the temporal terms (eq. 4.6), with identity
// and focal fixed. Given the next frame too (a smoothing pass,
// coarse_tracker.hpp), the temporal terms tie the frame to both neighbours.
// linearize() returns the residuals and their Jacobian with respect to the
// frame block (pose 6 + weights), robust weights applied (iteratively
// reweighted least squares), for the Gauss-Newton steps of frame_solver.hpp.
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/fit/fit_options.hpp"
#include "facecap/fit/frame_block.hpp"
#include "facecap/fit/landmark_basis.hpp"
#include "facecap/fit/landmark_cost.hpp"

namespace facecap {

class FrameEnergy {
 public:
  FrameEnergy(const LandmarkBasis& basis, const FitWeights& weights, const Landmarks& observed,
              const Eigen::Vector2d& principal_point, const Eigen::VectorXd& identity, double focal,
              const FrameParameters* previous, const FrameParameters* next = nullptr);

  void set_correspondences(const Correspondences& correspondences);
  // Gaussian pulls of expression weights (index, target) with one sigma,
  // replacing those set before: the gaze's eyeLook weights (face_fitter.hpp: GazeCue).
  void set_expression_targets(const std::vector<std::pair<int, double>>& targets, double sigma);
  int num_residuals() const { return rows_; }
  int block_size() const { return frame_block::size(num_expressions_); }
  double expression_l1() const { return weights_.expression_l1; }

  // Total cost 1/2 sum rho(||r_i||^2) (as Ceres defines it) + l1 * sum(w).
  double cost(const FrameParameters& x) const;
  // Cost, weighted residuals r and Jacobian J (rows x block_size). With
  // `shared` non-null, also the Jacobian of the same rows with respect to the
  // identity weights and the focal length (rows x (identity + 1)).
  double linearize(const FrameParameters& x, Eigen::VectorXd& r, Eigen::MatrixXd& jacobian,
                   Eigen::MatrixXd* shared = nullptr) const;
  // Changes the identity and focal the energy is evaluated with.
  void set_shared(const Eigen::VectorXd& identity, double focal);

  // Exposed for the identity solve, which adds the same landmark terms to Ceres.
  const std::array<LandmarkTerm, 68>& terms() const { return terms_; }

 private:
  void update_shaped();
  double landmark_block(int i, const FrameParameters& x, double* residual, double* jacobian_pose,
                        double* jacobian_expression, double* jacobian_identity = nullptr,
                        double* jacobian_focal = nullptr) const;

  const LandmarkBasis& basis_;
  const FitWeights& weights_;
  Eigen::VectorXd identity_;
  double focal_;
  int num_expressions_;
  std::array<LandmarkTerm, 68> terms_;
  // Each landmark's n + B_id a for the current identity and correspondences:
  // fixed within a frame's fit, so formed once rather than at every evaluation.
  std::array<Eigen::Vector3d, 68> shaped_;
  std::vector<std::unique_ptr<LandmarkCost>> costs_;
  std::vector<double> prior_index_, prior_mean_, prior_inv_sigma_;  // diagonal Gaussian rows
  size_t fixed_priors_ = 0;                                         // the rows before those of set_expression_targets
  int rows_ = 0;
};

// The sigma of each landmark in pixels (jaw looser), from the observation's size.
void set_landmark_observations(const Landmarks& observed, const FitWeights& weights,
                               const Eigen::Vector2d& principal_point, std::array<LandmarkTerm, 68>& terms);
void set_landmark_correspondences(const LandmarkBasis& basis, const Correspondences& correspondences,
                                  std::array<LandmarkTerm, 68>& terms);

}  // namespace facecap
