#include <cooperative_groups.h>

#include <algorithm>

#include "facecap/refine/cuda/block_reduce.cuh"
#include "facecap/refine/cuda/cooperative_launch.cuh"
#include "facecap/refine/cuda/displacement_kernels.cuh"

namespace facecap::cuda {

namespace {

namespace cg = cooperative_groups;

constexpr int kThreads = kBlockThreads;
constexpr int kMaxRing = 32;  // kMaxDisplacementRing (displacement_graph.hpp)

int blocks_for(int n) { return n > 0 ? (n + kThreads - 1) / kThreads : 1; }

struct V3 {
  float x, y, z;
};
__device__ inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
__device__ inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
__device__ inline V3 operator*(V3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
__device__ inline float dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
__device__ inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
__device__ inline V3 load(const float* p, int i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }

// Whether PCG iteration k runs: no earlier iteration stopped and r . z is not yet zero.
__device__ inline bool pcg_live(const double* s, int k) { return s[kLive + k] != 0.0 && s[kRz + k] > 1e-30; }

// The vector a pass multiplies. In PCG iteration k > 0 it is the search
// direction p_k = z_k + beta p_{k-1}, beta = (r.z)_k / (r.z)_{k-1}
// (Algorithm 2), formed where it is read: `x` holds p_{k-1} and `z` z_k
// until iteration k's update stores p_k, so no kernel of its own is needed.
struct Operand {
  const float* x = nullptr;
  const float* z = nullptr;  // null: x itself
  float beta = 0;

  __device__ Operand(const float* x_, const float* z_, const double* scalars, int k) : x(x_) {
    // (k = 0 or no z: x itself; scalars is read only for k > 0)
    if (z_ != nullptr && k > 0) {
      z = z_;
      beta = float(scalars[kRz + k] / scalars[kRz + k - 1]);
    }
  }
  __device__ float operator[](int i) const { return z ? z[i] + beta * x[i] : x[i]; }
};

__global__ void displace_kernel(GraphView g, FrameView f, const float* d) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  if (a >= g.counts[0]) return;
  const int i = g.global[a];
  for (int c = 0; c < 3; ++c) f.positions[3 * i + c] = f.base[3 * i + c] + d[a] * f.normals[3 * i + c];
}

// Linearisation of touched vertex t: Solver::linearise_vertex on the CPU.
__global__ void linearise_kernel(GraphView g, LevelView lv, FrameView f, LinearisationView lin, float huber,
                                 double* scalars) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  double cost = 0;
  if (t < g.counts[1]) {
    const int i = g.global[t];
    const V3 pi = load(f.positions, i);
    const V3 ni = load(f.normals, i);
    // m = sum over corners (j, k) of a x b, a = p_j - p_i, b = p_k - p_i;
    // dm/dd_i = n_i x sum (a - b), a ring vertex's dm/dd_s = n_s x u_s.
    V3 m{0, 0, 0}, sum_a_minus_b{0, 0, 0};
    V3 u[kMaxRing];
    for (int s = 0; s < kMaxRing; ++s) u[s] = {0, 0, 0};
    for (int c = lv.corner_offsets[i]; c < lv.corner_offsets[i + 1]; ++c) {
      const int j = lv.corners[2 * c], k = lv.corners[2 * c + 1];
      const int sj = lv.corner_slots[2 * c], sk = lv.corner_slots[2 * c + 1];
      const V3 a = load(f.positions, j) - pi, b = load(f.positions, k) - pi;
      m = m + cross(a, b);
      sum_a_minus_b = sum_a_minus_b + (a - b);
      if (sj >= 0 && sj < kMaxRing) u[sj] = u[sj] + b;
      if (sk >= 0 && sk < kMaxRing) u[sk] = u[sk] - a;
    }
    const int rb = g.row_offsets[t], re = g.row_offsets[t + 1];
    const float len = sqrtf(dot(m, m));
    float self = 0, weight = 0, residual = 0;
    if (len > 0) {
      const V3 n = m * (1.0f / len);
      // The SH basis is in the viewer frame (x, -y, -z); its gradient comes back the same way.
      const double vx = n.x, vy = -n.y, vz = -n.z;
      const double* l = f.lighting;
      const V3 gv{float(l[1] + l[4] * vy + l[5] * vz + 2 * l[7] * vx),
                  float(l[2] + l[4] * vx + l[6] * vz - 2 * l[7] * vy),
                  float(l[3] + l[5] * vx + l[6] * vy + 6 * l[8] * vz)};
      const V3 grad{gv.x, -gv.y, -gv.z};
      // ds/dm = g^T (I - n n^T) / |m|; ds/dm . (n x w) = w . (ds/dm x n).
      const V3 dsdm = (grad - n * dot(n, grad)) * (1.0f / len);
      self = dot(sum_a_minus_b, cross(dsdm, ni));
      for (int e = rb; e < re; ++e) {
        const int slot = g.row_slots[e];
        lin.jac[e] = slot < kMaxRing ? dot(u[slot], cross(dsdm, load(f.normals, g.row_vertices[e]))) : 0.0f;
      }
      if (f.visible[i]) {
        const float s = float(l[0] + l[1] * vx + l[2] * vy + l[3] * vz + l[4] * vx * vy + l[5] * vx * vz +
                              l[6] * vy * vz + l[7] * (vx * vx - vy * vy) + l[8] * (3 * vz * vz - 1));
        float w = 0, r = 0, e2 = 0;
        for (int c = 0; c < 3; ++c) {
          const float rho = f.albedo[3 * i + c];
          const float res = rho * s - f.colour[3 * i + c];
          w += rho * rho;
          r += rho * res;
          e2 += res * res;
        }
        // Huber on the vertex's residual, as reweighted least squares.
        float robust = 1.0f;
        if (huber > 0 && e2 > huber * huber) {
          const float e = sqrtf(e2);
          robust = huber / e;
          cost = 2 * huber * e - huber * huber;
        } else {
          cost = e2;
        }
        weight = robust * w;
        residual = robust * r;
      }
    } else {
      for (int e = rb; e < re; ++e) lin.jac[e] = 0;
    }
    lin.self[t] = self;
    lin.weight[t] = weight;
    lin.data_residual[t] = residual;
  }
  block_add(cost, scalars + kDataCost);
}

__global__ void gather_columns_kernel(GraphView g, LinearisationView lin) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  if (a >= g.counts[0]) return;
  for (int k = g.col_offsets[a]; k < g.col_offsets[a + 1]; ++k) {
    const int entry = g.col_entries[k];
    lin.jac_by_column[k] = entry >= 0 ? lin.jac[entry] : 0.0f;
  }
}

__global__ void regulariser_cost_kernel(GraphView g, Weights w, const float* d, const float* lx, const float* prolonged,
                                        const float* previous, double* scalars) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  double cost = 0;
  if (t < g.counts[1]) {
    cost = double(w.smooth) * double(lx[t]) * lx[t];
    if (t < g.counts[0]) {
      cost += double(w.coarse) * double(d[t]) * d[t];
      if (prolonged) cost += double(w.hierarchy) * double(d[t] - prolonged[t]) * (d[t] - prolonged[t]);
      if (previous) cost += double(w.temporal) * double(d[t] - previous[t]) * (d[t] - previous[t]);
    }
  }
  block_add(cost, scalars + kRegulariserCost);
}

// Row pass at touched vertex t: lx = L x and, with data, wgx = W G x.
template <bool kWithData>
__device__ void row_at(const GraphView& g, const LinearisationView& lin, const Operand& x, float* wgx, float* lx,
                       int t) {
  const float xt = t < g.counts[0] ? x[t] : 0.0f;
  float gx = 0, sum = 0;
  if constexpr (kWithData) gx = lin.self[t] * xt;
  for (int k = g.row_offsets[t]; k < g.row_offsets[t + 1]; ++k) {
    const float xs = x[g.row_cols[k]];
    if constexpr (kWithData) gx += lin.jac[k] * xs;
    sum += xs;
  }
  if constexpr (kWithData) wgx[t] = gx * lin.weight[t];
  const float inv = g.inv_degree[t];
  lx[t] = inv > 0 ? xt - sum * inv : 0.0f;
}

// Column pass at free vertex a: y = G^T u + smooth L^T v + c x; returns x . y there.
__device__ double column_at(const GraphView& g, const LinearisationView& lin, const float* u, const float* v, float c,
                            float smooth, const Operand& x, float* y, int a) {
  float data = lin.self[a] * u[a];
  float lap = g.inv_degree[a] > 0 ? v[a] : 0.0f;
  for (int k = g.col_offsets[a]; k < g.col_offsets[a + 1]; ++k) {
    const int t = g.col_rows[k];
    data += lin.jac_by_column[k] * u[t];
    lap -= v[t] * g.inv_degree[t];
  }
  const float xa = x[a];
  y[a] = data + (smooth * lap + c * xa);
  return double(xa) * y[a];
}

// The gradient's regularisers, the Jacobi preconditioner diag(J^T J) and the
// PCG's start from x = 0 at free vertex a; returns r . z there.
__device__ double pcg_start_at(const GraphView& g, const LinearisationView& lin, const Weights& w,
                               const NewtonVectors& v, const float* d, const float* prolonged, const float* previous,
                               int a) {
  float ga = v.grad[a];
  if (prolonged) ga += w.hierarchy * (d[a] - prolonged[a]);
  if (previous) ga += w.temporal * (d[a] - previous[a]);
  v.grad[a] = ga;
  float dd = lin.weight[a] * lin.self[a] * lin.self[a];
  float lap = g.inv_degree[a] > 0 ? 1.0f : 0.0f;
  for (int k = g.col_offsets[a]; k < g.col_offsets[a + 1]; ++k) {
    const int t = g.col_rows[k];
    const float j = lin.jac_by_column[k];
    dd += lin.weight[t] * j * j;
    lap += g.inv_degree[t] * g.inv_degree[t];
  }
  const float m = dd + w.smooth * lap + w.diag_const;
  v.diag[a] = m;
  v.x[a] = 0;
  v.r[a] = -ga;
  v.z[a] = -ga / m;
  v.p[a] = v.z[a];
  return double(v.r[a]) * v.z[a];
}

// The PCG update at free vertex a: stores this iteration's direction p_k,
// then x += alpha p, r -= alpha Ap, z = M^-1 r; returns the new r . z there.
__device__ double pcg_update_at(const NewtonVectors& v, const Operand& p, float alpha, int a) {
  const float pa = p[a];
  v.p[a] = pa;  // p_k, before z moves on
  v.x[a] += alpha * pa;
  v.r[a] -= alpha * v.ap[a];
  v.z[a] = v.r[a] / v.diag[a];
  return double(v.r[a]) * v.z[a];
}

// lx = L x over the touched vertices (the smoothness term of the energy).
__global__ void laplacian_kernel(GraphView g, const float* x_in, float* lx) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= g.counts[1]) return;
  row_at<false>(g, {}, Operand(x_in, nullptr, nullptr, 0), nullptr, lx, t);
}

// One Gauss-Newton step's normal equations at d, solved: the gradient J^T r,
// then Algorithm 2 from x0 = 0 for `iterations` iterations (or until r . z
// vanishes or p . Ap stops being positive), then grad . x. One cooperative
// launch whose passes wait for each other with grid.sync, so that the whole
// of Algorithm 2 reads as one function. On the H100 it measured about the
// same as one kernel per pass in a CUDA graph (a Gauss-Newton step 209-210
// against 218-224 us with its trial energy): at these sizes each pass is a
// few microseconds of dependent loads whichever way the passes are joined.
__global__ void __launch_bounds__(kThreads)
    newton_step_kernel(GraphView g, LinearisationView lin, Weights w, NewtonVectors v, const float* d,
                       const float* prolonged, const float* previous, double* scalars, int iterations) {
  const cg::grid_group grid = cg::this_grid();
  const int first = blockIdx.x * blockDim.x + threadIdx.x, stride = gridDim.x * blockDim.x;
  const int nf = g.counts[0], nt = g.counts[1];
  const Operand at_d(d, nullptr, nullptr, 0);
  for (int t = first; t < nt; t += stride) row_at<false>(g, lin, at_d, nullptr, v.lx, t);
  grid.sync();
  for (int a = first; a < nf; a += stride)
    column_at(g, lin, lin.data_residual, v.lx, w.coarse, w.smooth, at_d, v.grad, a);
  grid.sync();
  double sum = 0;
  for (int a = first; a < nf; a += stride) sum += pcg_start_at(g, lin, w, v, d, prolonged, previous, a);
  if (first == 0) scalars[kLive] = 1.0;
  block_add(sum, scalars + kRz);
  grid.sync();
  for (int k = 0; k < iterations; ++k) {
    if (!pcg_live(scalars, k)) break;  // the same for every thread: read after the sync
    const Operand p(v.p, v.z, scalars, k);
    for (int t = first; t < nt; t += stride) row_at<true>(g, lin, p, v.wgx, v.lx, t);
    grid.sync();
    sum = 0;
    for (int a = first; a < nf; a += stride) sum += column_at(g, lin, v.wgx, v.lx, w.diag_const, w.smooth, p, v.ap, a);
    block_add(sum, scalars + kPap + k);
    grid.sync();
    const bool live = scalars[kPap + k] > 0;
    if (first == 0) scalars[kLive + k + 1] = live ? 1.0 : 0.0;
    if (!live) break;
    const float alpha = float(scalars[kRz + k] / scalars[kPap + k]);
    sum = 0;
    for (int a = first; a < nf; a += stride) sum += pcg_update_at(v, p, alpha, a);
    block_add(sum, scalars + kRz + k + 1);
    grid.sync();
  }
  sum = 0;
  for (int a = first; a < nf; a += stride) sum += double(v.grad[a]) * v.x[a];
  block_add(sum, scalars + kGradDotStep);
}

__global__ void axpy_kernel(GraphView g, const float* a, float scale, const float* b, float* out) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < g.counts[0]) out[i] = a[i] + scale * b[i];
}

}  // namespace

void launch_displace(const GraphView& g, const FrameView& f, const float* d, cudaStream_t s) {
  displace_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, f, d);
}

void launch_linearise(const GraphView& g, const LevelView& lv, const FrameView& f, const LinearisationView& lin,
                      float huber, double* scalars, cudaStream_t s) {
  linearise_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, lv, f, lin, huber, scalars);
  gather_columns_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, lin);
}

void launch_laplacian(const GraphView& g, const float* x, float* lx, cudaStream_t s) {
  laplacian_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, x, lx);
}

void launch_regulariser_cost(const GraphView& g, const Weights& w, const float* d, const float* lx,
                             const float* prolonged, const float* previous, double* scalars, cudaStream_t s) {
  regulariser_cost_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, w, d, lx, prolonged, previous, scalars);
}

cudaError_t launch_newton_step(const GraphView& g, const LinearisationView& lin, const Weights& w,
                               const NewtonVectors& v, const float* d, const float* prolonged, const float* previous,
                               double* scalars, int iterations, cudaStream_t s) {
  // Every block must be resident at once for grid.sync: no more blocks than
  // the GPU holds (one thread per vertex fits on any GPU at these sizes; the
  // loops stride over the rest).
  static const int resident = resident_blocks(newton_step_kernel, kThreads);
  const int blocks = std::max(1, std::min(blocks_for(g.num_vertices), resident));
  return launch_cooperative(newton_step_kernel, blocks, kThreads, s, g, lin, w, v, d, prolonged, previous, scalars,
                            iterations);
}

void launch_axpy(const GraphView& g, const float* a, float scale, const float* b, float* out, cudaStream_t s) {
  axpy_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, a, scale, b, out);
}

}  // namespace facecap::cuda
