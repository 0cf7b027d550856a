#pragma once
// The linear system of one albedo estimate (§4.3.2, eq. 4.10) on a mesh
// level, per colour channel c:
//   (D + w L^T L) x_c = b_c + w L^T L prior_c,
// D the per-vertex data weights (the sum over frames of s_i^2), L the uniform
// graph Laplacian of the level's one-rings (L = I - A / r), solved by
// Jacobi-preconditioned conjugate gradients from a start, each channel with
// its own step sizes; a channel whose residual vanishes holds still. The CPU
// solver is the reference; the CUDA one (refine/cuda) keeps the level's rings
// on the GPU and runs all the iterations there in one cooperative kernel.
#include <memory>

#include <Eigen/Core>

#include "facecap/refine/compute_device.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"

namespace facecap {

// One row per vertex, one column per colour channel.
using AlbedoChannels = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// What the solvers share about a level: its rings, 1 / ring size (0 for an
// isolated vertex) and the diagonal of L^T L, 1 + sum over the ring of 1 / r_j^2.
struct AlbedoLaplacian {
  const VertexAdjacency* rings = nullptr;
  Eigen::VectorXd inv_degree;
  Eigen::VectorXd normal_diagonal;

  explicit AlbedoLaplacian(const MeshLevel& level);
  int num_vertices() const { return static_cast<int>(inv_degree.size()); }
};

class AlbedoSolver {
 public:
  virtual ~AlbedoSolver() = default;
  // d: n data weights; b, prior and start: n x 3. Returns x after at most
  // `iterations` CG iterations.
  virtual AlbedoChannels solve(const Eigen::VectorXd& d, const AlbedoChannels& b, double w, const AlbedoChannels& prior,
                               AlbedoChannels start, int iterations) = 0;
};

// Throws std::runtime_error for CUDA when this build has no CUDA backend or
// no CUDA device answers. The level must outlive the solver.
std::unique_ptr<AlbedoSolver> make_albedo_solver(ComputeDevice device, const MeshLevel& level);

}  // namespace facecap
