#include <cooperative_groups.h>

#include <algorithm>

#include "facecap/refine/cuda/albedo_kernels.cuh"
#include "facecap/refine/cuda/block_reduce.cuh"
#include "facecap/refine/cuda/cooperative_launch.cuh"

namespace facecap::cuda {

namespace {

namespace cg = cooperative_groups;

constexpr int kThreads = kBlockThreads;  // block_add's block size

// The CG's vectors, each 3 n channel-major, and its per-iteration sums.
struct PcgVectors {
  double *res, *z, *ap, *lx, *lx_start;
  double* p[2];     // the search direction, alternately written and read
  double* scalars;  // rz_k (3 per iteration, k = 0 .. iterations), then p.Ap_k (3 per iteration)
  int iterations;

  __device__ double& rz(int k, int c) const { return scalars[3 * k + c]; }
  __device__ double& pap(int k, int c) const { return scalars[3 * (iterations + 1) + 3 * k + c]; }
};

// (L v)_i with L = I - A / r.
__device__ double laplacian_at(const AlbedoRingsView& r, const double* v, int i) {
  double sum = 0.0;
  for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) sum += v[r.indices[s]];
  const double inv = r.inv_degree[i];
  return inv > 0.0 ? v[i] - sum * inv : 0.0;
}

// (L^T lx)_i = lx_i - sum over the ring of lx_j / r_j (the rings are symmetric).
__device__ double laplacian_transpose_at(const AlbedoRingsView& r, const double* lx, int i) {
  double sum = 0.0;
  for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
    const int j = r.indices[s];
    sum += lx[j] * r.inv_degree[j];
  }
  return lx[i] - sum;
}

__device__ double inverse_diagonal(const AlbedoRingsView& r, const double* d, double w, int i) {
  return 1.0 / (d[i] + w * r.normal_diagonal[i]);
}

// Blocks [c B, (c + 1) B) serve channel c; a converged channel's blocks only
// join the syncs. The loop's end is the same for every thread: it reads sums
// completed before the last sync.
__global__ void __launch_bounds__(kThreads)
    albedo_pcg_kernel(AlbedoRingsView r, const double* d, const double* b_all, const double* prior_all, double w,
                      double* x_all, PcgVectors v, int blocks_per_channel) {
  const cg::grid_group grid = cg::this_grid();
  const int n = r.num_vertices;
  const int c = blockIdx.x / blocks_per_channel;
  const int first = (blockIdx.x % blocks_per_channel) * blockDim.x + threadIdx.x;
  const int stride = blocks_per_channel * blockDim.x;
  const size_t off = size_t(c) * n;
  const double* b = b_all + off;
  const double* prior = prior_all + off;
  double* x = x_all + off;
  double *res = v.res + off, *z = v.z + off, *ap = v.ap + off, *lx = v.lx + off, *lx_start = v.lx_start + off;

  // res = (b + w L^T L prior) - (D x + w L^T L x), formed as the CPU forms it.
  for (int i = first; i < n; i += stride) {
    lx[i] = laplacian_at(r, prior, i);
    lx_start[i] = laplacian_at(r, x, i);
  }
  grid.sync();
  double sum = 0.0;
  for (int i = first; i < n; i += stride) {
    const double ri =
        (b[i] + w * laplacian_transpose_at(r, lx, i)) - (d[i] * x[i] + w * laplacian_transpose_at(r, lx_start, i));
    res[i] = ri;
    z[i] = inverse_diagonal(r, d, w, i) * ri;
    v.p[0][off + i] = z[i];
    sum += ri * z[i];
  }
  block_add(sum, &v.rz(0, c));
  grid.sync();

  for (int k = 0; k < v.iterations; ++k) {
    if (!(v.rz(k, 0) > 1e-20 || v.rz(k, 1) > 1e-20 || v.rz(k, 2) > 1e-20)) break;
    const bool live = v.rz(k, c) > 1e-20;  // else this channel holds still (and its rz stays 0)
    double* p = v.p[k & 1] + off;
    // lx = L p, with p = z + beta p_prev formed here for k > 0 (each block
    // writes its own vertices' p and reads its neighbours' z and p_prev).
    if (live) {
      if (k == 0) {
        for (int i = first; i < n; i += stride) lx[i] = laplacian_at(r, p, i);
      } else {
        const double* p_prev = v.p[(k - 1) & 1] + off;
        const double beta = v.rz(k, c) / v.rz(k - 1, c);
        for (int i = first; i < n; i += stride) {
          const double pi = z[i] + beta * p_prev[i];
          p[i] = pi;
          double ring = 0.0;
          for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
            const int j = r.indices[s];
            ring += z[j] + beta * p_prev[j];
          }
          const double inv = r.inv_degree[i];
          lx[i] = inv > 0.0 ? pi - ring * inv : 0.0;
        }
      }
    }
    grid.sync();
    sum = 0.0;
    if (live)
      for (int i = first; i < n; i += stride) {
        ap[i] = d[i] * p[i] + w * laplacian_transpose_at(r, lx, i);
        sum += p[i] * ap[i];
      }
    block_add(sum, &v.pap(k, c));
    grid.sync();
    sum = 0.0;
    if (live) {
      const double alpha = v.rz(k, c) / v.pap(k, c);
      for (int i = first; i < n; i += stride) {
        x[i] += alpha * p[i];
        res[i] -= alpha * ap[i];
        z[i] = inverse_diagonal(r, d, w, i) * res[i];
        sum += res[i] * z[i];
      }
    }
    block_add(sum, &v.rz(k + 1, c));
    grid.sync();
  }
}

int blocks_per_channel(int n) {
  static const int resident = resident_blocks(albedo_pcg_kernel, kThreads);
  return std::max(1, std::min((n + kThreads - 1) / kThreads, resident / 3));
}

}  // namespace

std::size_t albedo_pcg_scratch(int num_vertices, int iterations) {
  return 7 * 3 * std::size_t(num_vertices) + 6 * std::size_t(iterations + 1);
}

cudaError_t launch_albedo_pcg(const AlbedoRingsView& rings, const double* d, const double* b, const double* prior,
                              double w, int iterations, double* x, double* scratch, cudaStream_t stream) {
  const int n = rings.num_vertices;
  if (n <= 0) return cudaSuccess;
  const std::size_t size = 3 * std::size_t(n);
  PcgVectors v{scratch,
               scratch + size,
               scratch + 2 * size,
               scratch + 3 * size,
               scratch + 4 * size,
               {scratch + 5 * size, scratch + 6 * size},
               scratch + 7 * size,
               iterations};
  const cudaError_t cleared = cudaMemsetAsync(v.scalars, 0, 6 * std::size_t(iterations + 1) * sizeof(double), stream);
  if (cleared != cudaSuccess) return cleared;
  const int per_channel = blocks_per_channel(n);
  return launch_cooperative(albedo_pcg_kernel, 3 * per_channel, kThreads, stream, rings, d, b, prior, w, x, v,
                            per_channel);
}

}  // namespace facecap::cuda
