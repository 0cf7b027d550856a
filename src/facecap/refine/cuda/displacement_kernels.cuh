#pragma once
// The CUDA kernels of the displacement solve (§4.3.4): the linearisation of
// one Gauss-Newton step per touched vertex, the matrix-free products J^T J p
// as a row pass and a column pass, and the PCG's vector updates (Algorithm 2:
// three passes per iteration, the row pass, the column pass and the update).
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
// lx = L x over the touched vertices.
void launch_laplacian(const GraphView& g, const float* x, float* lx, cudaStream_t s);
// The energy's regularisers at d (lx = L d over the touched): into scalars[kRegulariserCost].
void launch_regulariser_cost(const GraphView& g, const Weights& w, const float* d, const float* lx,
                             const float* prolonged, const float* previous, double* scalars, cudaStream_t s);
// The PCG's vectors over the free vertices (wgx and lx over the touched).
struct NewtonVectors {
  float *grad = nullptr, *diag = nullptr, *x = nullptr, *r = nullptr, *z = nullptr, *p = nullptr, *ap = nullptr;
  float *wgx = nullptr, *lx = nullptr;
};
// One Gauss-Newton step's normal equations at d (linearised in `lin`): the
// gradient J^T r of the whole energy, the Jacobi preconditioner, Algorithm 2
// from x0 = 0 on (J^T J) x = -J^T r (each product a row pass and a column
// pass, three passes per iteration), and grad . x into scalars[kGradDotStep].
// One cooperative kernel; its passes wait for each other with grid.sync.
// Returns the launch's status (a cooperative launch can be refused).
cudaError_t launch_newton_step(const GraphView& g, const LinearisationView& lin, const Weights& w,
                               const NewtonVectors& v, const float* d, const float* prolonged, const float* previous,
                               double* scalars, int iterations, cudaStream_t s);
// out = a + scale b over the free vertices.
void launch_axpy(const GraphView& g, const float* a, float scale, const float* b, float* out, cudaStream_t s);

}  // namespace facecap::cuda
