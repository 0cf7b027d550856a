#pragma once
// One displacement solve (solve_displacements' contract) on a chosen device.
// A backend keeps its working memory across calls: the CUDA one keeps each
// level's topology and its buffers on the GPU from frame to frame.
#include <memory>

#include "facecap/refine/compute_device.hpp"
#include "facecap/refine/displacement_solver.hpp"

namespace facecap {

class DisplacementBackend {
 public:
  virtual ~DisplacementBackend() = default;
  virtual DisplacementReport solve(const DisplacementProblem& problem, Eigen::VectorXf& d,
                                   const DisplacementOptions& options) = 0;
};

// Throws std::runtime_error for CUDA when this build has no CUDA backend or
// no CUDA device answers.
std::unique_ptr<DisplacementBackend> make_displacement_backend(ComputeDevice device);

}  // namespace facecap
