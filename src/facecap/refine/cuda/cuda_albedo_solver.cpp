#include "facecap/refine/cuda/cuda_albedo_solver.hpp"

#include "facecap/refine/cuda/albedo_kernels.cuh"
#include "facecap/refine/cuda/device_buffer.hpp"

namespace facecap {

using cuda::check;
using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

struct CudaAlbedoSolver::State {
  cudaStream_t stream = nullptr;
  int num_vertices = 0;
  DeviceBuffer<int> offsets, indices;
  DeviceBuffer<double> inv_degree, normal_diagonal;
  // Per solve: d (n), then b, prior and x (3 n each, channel-major); and the CG's scratch.
  PinnedBuffer<double> staging;
  DeviceBuffer<double> inputs, scratch;

  State() { check(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate"); }
  ~State() { cudaStreamDestroy(stream); }

  cuda::AlbedoRingsView rings() const {
    return {num_vertices, offsets.get(), indices.get(), inv_degree.get(), normal_diagonal.get()};
  }
};

CudaAlbedoSolver::CudaAlbedoSolver(const MeshLevel& level) {
  require_cuda();
  state_ = std::make_unique<State>();
  State& s = *state_;
  const AlbedoLaplacian laplacian(level);
  s.num_vertices = level.num_vertices;
  s.offsets.upload(level.rings.offsets, s.stream);
  s.indices.upload(level.rings.indices, s.stream);
  s.inv_degree.upload(laplacian.inv_degree.data(), laplacian.inv_degree.size(), s.stream);
  s.normal_diagonal.upload(laplacian.normal_diagonal.data(), laplacian.normal_diagonal.size(), s.stream);
  check(cudaStreamSynchronize(s.stream), "copy to the GPU");  // the sources are pageable and die here
}

CudaAlbedoSolver::~CudaAlbedoSolver() = default;

AlbedoChannels CudaAlbedoSolver::solve(const Eigen::VectorXd& d, const AlbedoChannels& b, double w,
                                       const AlbedoChannels& prior, AlbedoChannels x, int iterations) {
  State& s = *state_;
  const int n = s.num_vertices;
  if (n == 0) return x;
  const std::size_t count = 10 * std::size_t(n);
  double* staged = s.staging.reserve(count);
  Eigen::Map<Eigen::VectorXd>(staged, n) = d;
  // Row-major n x 3 to channel-major 3 x n.
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>>(staged + n, 3, n) = b.transpose();
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>>(staged + 4 * n, 3, n) = prior.transpose();
  Eigen::Map<Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>>(staged + 7 * n, 3, n) = x.transpose();
  double* on_device = s.inputs.reserve(count);
  check(cudaMemcpyAsync(on_device, staged, count * sizeof(double), cudaMemcpyHostToDevice, s.stream),
        "copy to the GPU");
  double* const x_on_device = on_device + 7 * n;
  check(cuda::launch_albedo_pcg(s.rings(), on_device, on_device + n, on_device + 4 * n, w, iterations, x_on_device,
                                s.scratch.reserve(cuda::albedo_pcg_scratch(n, iterations)), s.stream),
        "cooperative launch of the albedo solve");
  check(cudaMemcpyAsync(staged + 7 * n, x_on_device, 3 * std::size_t(n) * sizeof(double), cudaMemcpyDeviceToHost,
                        s.stream),
        "copy from the GPU");
  check(cudaStreamSynchronize(s.stream), "albedo solve");
  x = Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>>(staged + 7 * n, 3, n).transpose();
  return x;
}

}  // namespace facecap
