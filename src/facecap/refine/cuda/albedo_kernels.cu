#include "facecap/refine/cuda/albedo_kernels.cuh"
#include "facecap/refine/cuda/block_reduce.cuh"

namespace facecap::cuda {

namespace {

// lx = L v over this block's channel (L = I - A / r).
__device__ void laplacian(const AlbedoRingsView& r, const double* v, double* lx) {
  for (int i = threadIdx.x; i < r.num_vertices; i += blockDim.x) {
    double sum = 0.0;
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) sum += v[r.indices[s]];
    const double inv = r.inv_degree[i];
    lx[i] = inv > 0.0 ? v[i] - sum * inv : 0.0;
  }
}

// out_i = (L^T lx)_i = lx_i - sum over the ring of lx_j / r_j (the rings are symmetric).
__device__ double laplacian_transpose_at(const AlbedoRingsView& r, const double* lx, int i) {
  double sum = 0.0;
  for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
    const int j = r.indices[s];
    sum += lx[j] * r.inv_degree[j];
  }
  return lx[i] - sum;
}

// One block per channel: blockIdx.x = c.
__global__ void __launch_bounds__(kAlbedoThreads)
    albedo_pcg_kernel(AlbedoRingsView r, const double* d, const double* b_all, const double* prior_all, double w,
                      int iterations, double* x_all, double* scratch) {
  const int n = r.num_vertices, c = blockIdx.x;
  const double* b = b_all + size_t(c) * n;
  const double* prior = prior_all + size_t(c) * n;
  double* x = x_all + size_t(c) * n;
  double* res = scratch + size_t(c) * n;
  double* z = res + 3 * size_t(n);
  double* p = z + 3 * size_t(n);
  double* ap = p + 3 * size_t(n);
  double* lx = ap + 3 * size_t(n);
  double* lx_start = lx + 3 * size_t(n);

  // res = b + w L^T L prior - (D x + w L^T L x) = b - D x + w L^T L (prior - x),
  // formed as the CPU forms it: both Laplacian products, then the sums.
  laplacian(r, prior, lx);
  laplacian(r, x, lx_start);
  __syncthreads();
  double rz_local = 0.0;
  for (int i = threadIdx.x; i < n; i += blockDim.x) {
    const double llx_prior = laplacian_transpose_at(r, lx, i);
    const double llx_x = laplacian_transpose_at(r, lx_start, i);
    const double inv_diag = 1.0 / (d[i] + w * r.normal_diagonal[i]);
    const double ri = (b[i] + w * llx_prior) - (d[i] * x[i] + w * llx_x);
    res[i] = ri;
    z[i] = inv_diag * ri;
    p[i] = z[i];
    rz_local += ri * z[i];
  }
  double rz = block_sum<kAlbedoThreads>(rz_local);

  for (int k = 0; k < iterations && rz > 1e-20; ++k) {
    laplacian(r, p, lx);
    __syncthreads();
    double pap_local = 0.0;
    for (int i = threadIdx.x; i < n; i += blockDim.x) {
      ap[i] = d[i] * p[i] + w * laplacian_transpose_at(r, lx, i);
      pap_local += p[i] * ap[i];
    }
    const double alpha = rz / block_sum<kAlbedoThreads>(pap_local);
    double rz_new_local = 0.0;
    for (int i = threadIdx.x; i < n; i += blockDim.x) {
      x[i] += alpha * p[i];
      res[i] -= alpha * ap[i];
      z[i] = (1.0 / (d[i] + w * r.normal_diagonal[i])) * res[i];
      rz_new_local += res[i] * z[i];
    }
    const double rz_new = block_sum<kAlbedoThreads>(rz_new_local);
    const double beta = rz_new / rz;
    for (int i = threadIdx.x; i < n; i += blockDim.x) p[i] = z[i] + beta * p[i];
    rz = rz_new;
    __syncthreads();  // p complete before the next Laplacian reads it
  }
}

}  // namespace

void launch_albedo_pcg(const AlbedoRingsView& rings, const double* d, const double* b, const double* prior, double w,
                       int iterations, double* x, double* scratch, cudaStream_t stream) {
  if (rings.num_vertices <= 0) return;
  albedo_pcg_kernel<<<3, kAlbedoThreads, 0, stream>>>(rings, d, b, prior, w, iterations, x, scratch);
}

}  // namespace facecap::cuda
