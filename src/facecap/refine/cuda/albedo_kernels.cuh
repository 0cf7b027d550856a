#pragma once
// The albedo estimate's conjugate gradients (albedo_solver.hpp) on the GPU:
// all the iterations of the three channels' Jacobi-preconditioned CG in one
// cooperative kernel, each channel on its own share of the blocks, the passes
// of an iteration joined by grid-wide syncs (three per iteration: the search
// direction is formed where the Laplacian pass reads it).
#include <cuda_runtime.h>

namespace facecap::cuda {

struct AlbedoRingsView {
  int num_vertices = 0;
  const int* offsets = nullptr;  // n + 1
  const int* indices = nullptr;
  const double* inv_degree = nullptr;       // 1 / ring size, 0 for an isolated vertex
  const double* normal_diagonal = nullptr;  // diag(L^T L)
};

// Doubles of scratch launch_albedo_pcg needs for n vertices and an iteration count.
std::size_t albedo_pcg_scratch(int num_vertices, int iterations);

// Channel-major arrays (channel c's n values at c n). d: n data weights;
// b, prior: 3 n; x: 3 n, the start in and the solution out.
cudaError_t launch_albedo_pcg(const AlbedoRingsView& rings, const double* d, const double* b, const double* prior,
                              double w, int iterations, double* x, double* scratch, cudaStream_t stream);

}  // namespace facecap::cuda
