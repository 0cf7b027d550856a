#include "facecap/refine/displacement_backend.hpp"

#if FACECAP_HAVE_CUDA
#include "facecap/refine/cuda/cuda_displacement_solver.hpp"
#endif

namespace facecap {

namespace {

class CpuDisplacementBackend final : public DisplacementBackend {
 public:
  DisplacementReport solve(const DisplacementProblem& problem, Eigen::VectorXf& d,
                           const DisplacementOptions& options) override {
    return solve_displacements(problem, d, options);
  }
};

#if FACECAP_HAVE_CUDA
class CudaDisplacementBackend final : public DisplacementBackend {
 public:
  DisplacementReport solve(const DisplacementProblem& problem, Eigen::VectorXf& d,
                           const DisplacementOptions& options) override {
    return solver_.solve(problem, d, options);
  }

 private:
  CudaDisplacementSolver solver_;
};
#endif

}  // namespace

std::unique_ptr<DisplacementBackend> make_displacement_backend(ComputeDevice device) {
  if (device == ComputeDevice::cpu) return std::make_unique<CpuDisplacementBackend>();
  require_cuda();
#if FACECAP_HAVE_CUDA
  return std::make_unique<CudaDisplacementBackend>();
#else
  return nullptr;  // not reached: require_cuda throws in a build without CUDA
#endif
}

}  // namespace facecap
