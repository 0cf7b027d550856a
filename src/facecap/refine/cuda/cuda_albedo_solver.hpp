#pragma once
// The albedo estimate's conjugate gradients (albedo_solver.hpp) on an NVIDIA
// GPU: the level's rings go to the device once; each solve uploads the data
// weights, right-hand sides, prior and start in one copy and reads back the
// solution. Built only with FACECAP_CUDA; plain C++ interface (no CUDA types).
#include <memory>

#include "facecap/refine/albedo_solver.hpp"

namespace facecap {

class CudaAlbedoSolver final : public AlbedoSolver {
 public:
  // Throws std::runtime_error when no CUDA device answers (require_cuda).
  explicit CudaAlbedoSolver(const MeshLevel& level);
  ~CudaAlbedoSolver() override;
  CudaAlbedoSolver(const CudaAlbedoSolver&) = delete;
  CudaAlbedoSolver& operator=(const CudaAlbedoSolver&) = delete;

  AlbedoChannels solve(const Eigen::VectorXd& d, const AlbedoChannels& b, double w, const AlbedoChannels& prior,
                       AlbedoChannels start, int iterations) override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace facecap
