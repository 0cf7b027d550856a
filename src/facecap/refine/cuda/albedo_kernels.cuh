#pragma once
// The albedo estimate's conjugate gradients (albedo_solver.hpp) on the GPU:
// one thread block per colour channel runs all the iterations of its
// channel's Jacobi-preconditioned CG, joined by __syncthreads alone (a level
// of about 9.4k vertices fits one block's passes; the channels are
// independent, so the blocks never wait on each other).
#include <cuda_runtime.h>

namespace facecap::cuda {

constexpr int kAlbedoThreads = 1024;  // threads per channel's block

struct AlbedoRingsView {
  int num_vertices = 0;
  const int* offsets = nullptr;  // n + 1
  const int* indices = nullptr;
  const double* inv_degree = nullptr;       // 1 / ring size, 0 for an isolated vertex
  const double* normal_diagonal = nullptr;  // diag(L^T L)
};

// Channel-major arrays (channel c's n values at c n). d: n data weights;
// b, prior: 3 n; x: 3 n, the start in and the solution out. scratch: 6 x 3 n
// doubles (residual, preconditioned residual, direction, its product, and
// two Laplacian passes).
void launch_albedo_pcg(const AlbedoRingsView& rings, const double* d, const double* b, const double* prior, double w,
                       int iterations, double* x, double* scratch, cudaStream_t stream);

}  // namespace facecap::cuda
