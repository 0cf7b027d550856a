#pragma once
// The CUDA kernels of the displacement solve (§4.3.4): the linearisation of
// one Gauss-Newton step per touched vertex, the matrix-free products J^T J p
// as a row pass and a column pass, and the PCG's vector updates (Algorithm 2:
// three kernels per iteration, the row pass, the column pass and the update).
// Plain data views only: this header is read by nvcc and by the host code,
// and holds no Eigen.
//
// The numbering is DisplacementGraph's (displacement_graph.hpp): free
// vertices [0, num_free), the other touched ones after them. The CPU solver
// (displacement_solver.cpp) is the reference these kernels follow step by step.
#include <cuda_runtime.h>

namespace facecap::cuda {

// The level's fixed topology, resident on the device across frames.
struct LevelView {
  int num_vertices = 0;
  const int* corner_offsets = nullptr;  // num_vertices + 1
  const int* corners = nullptr;         // pairs (j, k) per incident triangle
  const int* corner_slots = nullptr;    // pairs: the corners' slots in the vertex's ring
};

// One frame's data at the level (3 floats per vertex, xyz or RGB).
struct FrameView {
  const float* base = nullptr;
  const float* normals = nullptr;
  const float* albedo = nullptr;
  const float* colour = nullptr;
  const unsigned char* visible = nullptr;
  float* positions = nullptr;        // the displaced surface (the base where d is fixed)
  const double* lighting = nullptr;  // the 9 SH coefficients
};

// The solve's graph, per frame (the free set follows what the camera sees).
// Its sizes live on the device (counts[0] free, counts[1] touched vertices),
// so that a frame's launches need no round trip to the host: every pass
// launches over the level's vertex count and skips what lies beyond.
struct GraphView {
  int num_vertices = 0;
  const int* counts = nullptr;
  const int* global = nullptr;
  const float* inv_degree = nullptr;
  const int *row_offsets = nullptr, *row_cols = nullptr, *row_slots = nullptr, *row_vertices = nullptr;
  const int *col_offsets = nullptr, *col_rows = nullptr, *col_entries = nullptr;
};

// One linearisation (see Linearisation in displacement_solver.cpp).
struct LinearisationView {
  float *self = nullptr, *jac = nullptr, *jac_by_column = nullptr, *weight = nullptr, *data_residual = nullptr;
};

struct Weights {
  float smooth = 0, hierarchy = 0, temporal = 0, coarse = 0;
  float diag_const = 0;  // coarse + temporal + hierarchy where present
};

// Slots of the device array of double scalars.
constexpr int kMaxPcgIterations = 64;
enum ScalarSlot : int {
  kDataCost = 0,
  kRegulariserCost = 1,
  kProlongedFixed = 2,  // the squares of pd where d is fixed (E_hier's constant share)
  kPreviousFixed = 3,   // the same of d_prev (E_temp's)
  kGradDotStep = 4,
  kRz = 5,                             // r . z before each PCG iteration, kMaxPcgIterations + 1
  kPap = kRz + kMaxPcgIterations + 1,  // p . A p of each iteration
  kLive = kPap + kMaxPcgIterations,    // 1 while the PCG runs, kMaxPcgIterations + 1
  kScalarCount = kLive + kMaxPcgIterations + 1
};

// positions[global[a]] = base + d[a] normal, over the free vertices.
void launch_displace(const GraphView& g, const FrameView& f, const float* d, cudaStream_t s);
// Shading derivatives and the (Huber) data residual of every touched vertex;
// the data cost is added to scalars[kDataCost].
void launch_linearise(const GraphView& g, const LevelView& lv, const FrameView& f, const LinearisationView& lin,
                      float huber, double* scalars, cudaStream_t s);
// lx = L x over the touched vertices; with `lin`, also wgx = W G x. With
// pcg_iteration >= 0 the pass runs only while that PCG iteration is live,
// and x is the search direction formed from the previous one and z (z may
// be null outside the PCG).
void launch_rows(const GraphView& g, const LinearisationView* lin, const float* x, const float* z, float* wgx,
                 float* lx, const double* scalars, int pcg_iteration, cudaStream_t s);
// y = G^T u + smooth L^T v + c x over the free vertices; with pcg_iteration
// >= 0 it is gated and formed like launch_rows and x . y goes to scalars[kPap + it].
void launch_columns(const GraphView& g, const LinearisationView& lin, const float* u, const float* v, float c,
                    float smooth, const float* x, const float* z, float* y, double* scalars, int pcg_iteration,
                    cudaStream_t s);
// The energy's regularisers at d (lx = L d over the touched): into scalars[kRegulariserCost].
void launch_regulariser_cost(const GraphView& g, const Weights& w, const float* d, const float* lx,
                             const float* prolonged, const float* previous, double* scalars, cudaStream_t s);
// Finishes the gradient (E_hier, E_temp), forms the Jacobi preconditioner and
// starts the PCG from x = 0: r = -grad, z = M^-1 r, p = z, r . z.
void launch_pcg_start(const GraphView& g, const LinearisationView& lin, const Weights& w, const float* d,
                      const float* prolonged, const float* previous, float* grad, float* diag, float* x, float* r,
                      float* z, float* p, double* scalars, cudaStream_t s);
// Stores this iteration's direction p, then x += alpha p, r -= alpha Ap,
// z = M^-1 r and the new r . z.
void launch_pcg_update(const GraphView& g, float* p, const float* ap, const float* diag, float* x, float* r, float* z,
                       double* scalars, int pcg_iteration, cudaStream_t s);
// scalars[slot] += a . b over the free vertices.
void launch_dot(const GraphView& g, const float* a, const float* b, double* scalars, int slot, cudaStream_t s);
// out = a + scale b over the free vertices.
void launch_axpy(const GraphView& g, const float* a, float scale, const float* b, float* out, cudaStream_t s);

}  // namespace facecap::cuda
