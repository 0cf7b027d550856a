#include "facecap/refine/cuda/displacement_kernels.cuh"

namespace facecap::cuda {

namespace {

constexpr int kThreads = 256;
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

// Sums `value` over the block and adds the block's sum to *out (one atomic per block).
__device__ void block_add(double value, double* out) {
  __shared__ double partial[kThreads / 32];
  for (int offset = 16; offset > 0; offset /= 2) value += __shfl_down_sync(0xffffffffu, value, offset);
  const int lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  if (lane == 0) partial[warp] = value;
  __syncthreads();
  if (warp == 0) {
    value = lane < kThreads / 32 ? partial[lane] : 0.0;
    for (int offset = 16; offset > 0; offset /= 2) value += __shfl_down_sync(0xffffffffu, value, offset);
    if (lane == 0 && value != 0.0) atomicAdd(out, value);
  }
}

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

template <bool kWithData>
__global__ void rows_kernel(GraphView g, LinearisationView lin, const float* x_in, const float* z, float* wgx,
                            float* lx, const double* scalars, int pcg_iteration) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= g.counts[1]) return;
  if (pcg_iteration >= 0 && !pcg_live(scalars, pcg_iteration)) return;
  const Operand x(x_in, z, scalars, pcg_iteration);
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

__global__ void columns_kernel(GraphView g, LinearisationView lin, const float* u, const float* v, float c,
                               float smooth, const float* x_in, const float* z, float* y, double* scalars,
                               int pcg_iteration) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  const bool gated = pcg_iteration >= 0;
  if (gated && !pcg_live(scalars, pcg_iteration)) return;  // uniform over the grid
  const Operand x(x_in, z, scalars, pcg_iteration);
  double xy = 0;
  if (a < g.counts[0]) {
    float data = lin.self[a] * u[a];
    float lap = g.inv_degree[a] > 0 ? v[a] : 0.0f;
    for (int k = g.col_offsets[a]; k < g.col_offsets[a + 1]; ++k) {
      const int t = g.col_rows[k];
      data += lin.jac_by_column[k] * u[t];
      lap -= v[t] * g.inv_degree[t];
    }
    y[a] = data + (smooth * lap + c * x[a]);
    xy = double(x[a]) * y[a];
  }
  if (gated) block_add(xy, scalars + kPap + pcg_iteration);
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

__global__ void pcg_start_kernel(GraphView g, LinearisationView lin, Weights w, const float* d, const float* prolonged,
                                 const float* previous, float* grad, float* diag, float* x, float* r, float* z,
                                 float* p, double* scalars) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  if (a == 0) scalars[kLive] = 1.0;
  double rz = 0;
  if (a < g.counts[0]) {
    float ga = grad[a];
    if (prolonged) ga += w.hierarchy * (d[a] - prolonged[a]);
    if (previous) ga += w.temporal * (d[a] - previous[a]);
    grad[a] = ga;
    // Jacobi preconditioner: diag(J^T J).
    float dd = lin.weight[a] * lin.self[a] * lin.self[a];
    float lap = g.inv_degree[a] > 0 ? 1.0f : 0.0f;
    for (int k = g.col_offsets[a]; k < g.col_offsets[a + 1]; ++k) {
      const int t = g.col_rows[k];
      const float j = lin.jac_by_column[k];
      dd += lin.weight[t] * j * j;
      lap += g.inv_degree[t] * g.inv_degree[t];
    }
    const float m = dd + w.smooth * lap + w.diag_const;
    diag[a] = m;
    x[a] = 0;
    r[a] = -ga;
    z[a] = -ga / m;
    p[a] = z[a];
    rz = double(r[a]) * z[a];
  }
  block_add(rz, scalars + kRz);
}

__global__ void pcg_update_kernel(GraphView g, float* p, const float* ap, const float* diag, float* x, float* r,
                                  float* z, double* scalars, int k) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  const bool live = pcg_live(scalars, k) && scalars[kPap + k] > 0;
  if (a == 0) scalars[kLive + k + 1] = live ? 1.0 : 0.0;
  if (!live) return;  // uniform over the grid
  const float alpha = float(scalars[kRz + k] / scalars[kPap + k]);
  double rz = 0;
  if (a < g.counts[0]) {
    const float pa = Operand(p, z, scalars, k)[a];
    p[a] = pa;  // p_k, before z moves on
    x[a] += alpha * pa;
    r[a] -= alpha * ap[a];
    z[a] = r[a] / diag[a];
    rz = double(r[a]) * z[a];
  }
  block_add(rz, scalars + kRz + k + 1);
}

__global__ void dot_kernel(GraphView g, const float* a, const float* b, double* out) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  block_add(i < g.counts[0] ? double(a[i]) * b[i] : 0.0, out);
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

void launch_rows(const GraphView& g, const LinearisationView* lin, const float* x, const float* z, float* wgx,
                 float* lx, const double* scalars, int pcg_iteration, cudaStream_t s) {
  if (lin)
    rows_kernel<true><<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, *lin, x, z, wgx, lx, scalars, pcg_iteration);
  else
    rows_kernel<false><<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, {}, x, z, wgx, lx, scalars, pcg_iteration);
}

void launch_columns(const GraphView& g, const LinearisationView& lin, const float* u, const float* v, float c,
                    float smooth, const float* x, const float* z, float* y, double* scalars, int pcg_iteration,
                    cudaStream_t s) {
  columns_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, lin, u, v, c, smooth, x, z, y, scalars,
                                                                 pcg_iteration);
}

void launch_regulariser_cost(const GraphView& g, const Weights& w, const float* d, const float* lx,
                             const float* prolonged, const float* previous, double* scalars, cudaStream_t s) {
  regulariser_cost_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, w, d, lx, prolonged, previous, scalars);
}

void launch_pcg_start(const GraphView& g, const LinearisationView& lin, const Weights& w, const float* d,
                      const float* prolonged, const float* previous, float* grad, float* diag, float* x, float* r,
                      float* z, float* p, double* scalars, cudaStream_t s) {
  pcg_start_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, lin, w, d, prolonged, previous, grad, diag, x, r,
                                                                   z, p, scalars);
}

void launch_pcg_update(const GraphView& g, float* p, const float* ap, const float* diag, float* x, float* r, float* z,
                       double* scalars, int pcg_iteration, cudaStream_t s) {
  pcg_update_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, p, ap, diag, x, r, z, scalars, pcg_iteration);
}

void launch_dot(const GraphView& g, const float* a, const float* b, double* scalars, int slot, cudaStream_t s) {
  dot_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, a, b, scalars + slot);
}

void launch_axpy(const GraphView& g, const float* a, float scale, const float* b, float* out, cudaStream_t s) {
  axpy_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, a, scale, b, out);
}

}  // namespace facecap::cuda
