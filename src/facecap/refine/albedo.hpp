#pragma once
// Albedo recovery, §4.3.2, eq. 4.10: per-vertex RGB albedo rho on the
// coarsest level,
//   E(rho) = sum_frames sum_i visible (rho_ic s_i - I_ic)^2 + w2 ||L rho - L rho_bar||^2,
// s_i = l^T SH(n_i), L the graph Laplacian (uniform one-ring weights),
// w2 = 0.5, solved per channel by Jacobi-preconditioned conjugate gradients
// (100 iterations) over the first frames, then held fixed.
//
// The prior rho_bar (FaceWarehouse's mean albedo in the paper; ICT has none,
// DESIGN.md) is the same data solved with a much stronger Laplacian weight: a
// smooth albedo estimated from the first frames, which also fills vertices
// no frame has seen.
#include <memory>

#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/refine/albedo_solver.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/refine/vertex_samples.hpp"

namespace facecap {

struct AlbedoOptions {
  int frames = 10;                // frames accumulated before the albedo is fixed
  int interval = 3;               // take every this-many-th frame: more head motion, less lighting/albedo ambiguity
  double laplacian_weight = 0.5;  // w2 of eq. 4.10
  double prior_smoothing = 50.0;  // Laplacian weight of the smooth prior rho_bar
  int pcg_iterations = 100;
};

class AlbedoEstimator {
 public:
  // The level must outlive the estimator; `device` runs the PCG (albedo_solver.hpp).
  AlbedoEstimator(const MeshLevel& level, AlbedoOptions options = {}, ComputeDevice device = ComputeDevice::cpu);

  // Adds one frame's visible samples with the shading s_i = l^T SH(n_i).
  void add_frame(const VertexSamples& samples, const Positions& camera_normals, const ShCoeffs& lighting);
  // Solves eq. 4.10 with everything added so far.
  void solve();
  // Drops the accumulated data (before re-adding frames with new lightings).
  void clear_data();
  // A uniform starting albedo: the mean visible colour.
  void initialise_uniform(const VertexSamples& samples);

  const Positions& albedo() const { return albedo_; }  // 3 x N, RGB
  int frames() const { return frames_; }
  bool fixed() const { return frames_ >= options_.frames; }

 private:
  const MeshLevel& level_;
  AlbedoOptions options_;
  std::unique_ptr<AlbedoSolver> solver_;
  Eigen::VectorXd data_diag_;  // sum over frames of s_i^2
  Eigen::Matrix3Xd data_rhs_;  // sum over frames of s_i I_ic
  Positions albedo_;
  int frames_ = 0;
};

}  // namespace facecap
