#pragma once
// The displacement solve of §4.3.4 on an NVIDIA GPU: the same energy, the same
// Gauss-Newton steps and step halving and the same Jacobi-preconditioned CG as
// solve_displacements (the CPU reference), with J^T J applied matrix-free by
// kernels. Each level's topology stays on the device across frames; a frame
// uploads its base surface, normals, albedo, samples and graph, and reads
// back d. Built only with FACECAP_CUDA; plain C++ interface (no CUDA types).
#include <memory>

#include "facecap/refine/compute_device.hpp"
#include "facecap/refine/displacement_solver.hpp"

namespace facecap {

class CudaDisplacementSolver {
 public:
  // Throws std::runtime_error when no CUDA device answers (require_cuda).
  CudaDisplacementSolver();
  ~CudaDisplacementSolver();
  CudaDisplacementSolver(const CudaDisplacementSolver&) = delete;
  CudaDisplacementSolver& operator=(const CudaDisplacementSolver&) = delete;

  DisplacementReport solve(const DisplacementProblem& problem, Eigen::VectorXf& d,
                           const DisplacementOptions& options = {});

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace facecap
