#include "facecap/refine/cuda/cuda_displacement_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "facecap/core/stopwatch.hpp"
#include "facecap/refine/cuda/device_buffer.hpp"
#include "facecap/refine/cuda/displacement_graph_kernels.cuh"
#include "facecap/refine/cuda/displacement_kernels.cuh"
#include "facecap/refine/displacement_graph.hpp"

namespace facecap {

namespace cuda {

void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess) throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(status));
}

}  // namespace cuda

using cuda::check;
using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

bool cuda_device_available() {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();  // clear the sticky "no device" error
    return false;
  }
  return count > 0;
}

namespace {

// A level's topology on the device. A MeshLevel does not change once its
// hierarchy is built, so it is uploaded once and found again by address.
struct LevelOnDevice {
  int num_vertices = 0;
  std::size_t num_corners = 0, num_ring_entries = 0;
  DeviceBuffer<int> corner_offsets, corners, corner_slots, ring_offsets, ring_indices, ring_transpose;
  DeviceBuffer<unsigned char> boundary;

  cuda::LevelView view() const { return {num_vertices, corner_offsets.get(), corners.get(), corner_slots.get()}; }
  cuda::RingsView rings() const {
    return {num_vertices,         static_cast<int>(num_ring_entries),
            ring_offsets.get(),   ring_indices.get(),
            ring_transpose.get(), boundary.get()};
  }
};

struct LinearisationOnDevice {
  DeviceBuffer<float> self, jac, jac_by_column, weight, data_residual;

  // Sized for any graph of a level with n vertices and r ring entries.
  cuda::LinearisationView reserve(std::size_t n, std::size_t r) {
    return {self.reserve(n), jac.reserve(r), jac_by_column.reserve(r), weight.reserve(n), data_residual.reserve(n)};
  }
};

// One Gauss-Newton step as a CUDA graph: its ~40 small kernels launched at
// once instead of one by one (on these problems the launches, not the
// arithmetic, set the pace). Captured from the stream at each solve, since
// the frame's buffers and sizes are baked in; the executable graph is
// updated in place when its shape is unchanged.
class StepGraph {
 public:
  StepGraph() = default;
  ~StepGraph() {
    if (exec_) cudaGraphExecDestroy(exec_);
  }
  StepGraph(const StepGraph&) = delete;
  StepGraph& operator=(const StepGraph&) = delete;

  void begin_capture(cudaStream_t stream) {
    check(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal), "graph capture");
  }
  void end_capture(cudaStream_t stream) {
    cudaGraph_t graph = nullptr;
    check(cudaStreamEndCapture(stream, &graph), "graph capture");
    bool updated = false;
    if (exec_) {
      cudaGraphExecUpdateResultInfo info;
      updated = cudaGraphExecUpdate(exec_, graph, &info) == cudaSuccess;
      if (!updated) {
        cudaGetLastError();
        cudaGraphExecDestroy(exec_);
        exec_ = nullptr;
      }
    }
    cudaError_t status = cudaSuccess;
    if (!updated) status = cudaGraphInstantiate(&exec_, graph, 0);
    cudaGraphDestroy(graph);
    check(status, "graph instantiation");
  }
  void launch(cudaStream_t stream) { check(cudaGraphLaunch(exec_, stream), "graph launch"); }

 private:
  cudaGraphExec_t exec_ = nullptr;
};

// Where each of the frame's arrays sits in the one upload: the lighting's 9
// doubles, then the floats, then the bytes.
struct FrameLayout {
  std::size_t base, normals, albedo, colour, d, prolonged, previous, floats;  // in floats
  std::size_t visible, active, bytes;                                         // in bytes, after the floats
};
constexpr std::size_t kLightingFloats = 18;  // 9 doubles

FrameLayout frame_layout(std::size_t n, bool prolonged, bool previous, bool active) {
  FrameLayout l{};
  std::size_t at = kLightingFloats;
  const auto take = [&](std::size_t count) {
    const std::size_t here = at;
    at += count;
    return here;
  };
  l.base = take(3 * n);
  l.normals = take(3 * n);
  l.albedo = take(3 * n);
  l.colour = take(3 * n);
  l.d = take(n);
  l.prolonged = take(prolonged ? n : 0);
  l.previous = take(previous ? n : 0);
  l.floats = at;
  l.visible = at * sizeof(float);
  l.active = l.visible + n;
  l.bytes = l.active + (active ? n : 0);
  return l;
}

}  // namespace

struct CudaDisplacementSolver::State {
  cudaStream_t stream = nullptr;
  std::map<const MeshLevel*, LevelOnDevice> levels;
  PinnedBuffer<unsigned char> staging;
  DeviceBuffer<unsigned char> frame;  // the frame's arrays, as staged
  DeviceBuffer<float> positions, d_full;
  // The graph and its construction.
  DeviceBuffer<int> is_free, is_touched, free_rank, touched_rank, local, row_count, col_count, slot_entry;
  DeviceBuffer<int> global, row_offsets, row_cols, row_slots, row_vertices, col_offsets, col_rows, col_entries;
  DeviceBuffer<int> counts;
  DeviceBuffer<float> inv_degree;
  DeviceBuffer<unsigned char> scan_scratch;
  // The solve's vectors.
  DeviceBuffer<float> d, trial, prolonged, previous, grad, diag, x, r, z, p, ap, wgx, lx;
  LinearisationOnDevice lin[2];
  DeviceBuffer<double> scalars;
  PinnedBuffer<double> readback;
  // One Gauss-Newton step's graph per level, kept while what it was captured
  // with (buffers, sizes, weights) stays the same: bytes of those views.
  struct CachedStep {
    std::string signature;
    StepGraph graph;
  };
  std::map<const MeshLevel*, CachedStep> steps;

  State() { check(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate"); }
  ~State() { cudaStreamDestroy(stream); }

  const LevelOnDevice& level(const MeshLevel& lv) {
    LevelOnDevice& dev = levels[&lv];
    if (dev.num_vertices != lv.num_vertices || dev.num_corners != lv.corners.size() ||
        dev.num_ring_entries != lv.rings.indices.size()) {
      dev.num_vertices = lv.num_vertices;
      dev.num_corners = lv.corners.size();
      dev.num_ring_entries = lv.rings.indices.size();
      dev.corner_offsets.upload(lv.corner_offsets, stream);
      dev.corners.upload(lv.corners.empty() ? nullptr : lv.corners.front().data(), 2 * lv.corners.size(), stream);
      dev.corner_slots.upload(lv.corner_slots.empty() ? nullptr : lv.corner_slots.front().data(),
                              2 * lv.corner_slots.size(), stream);
      dev.ring_offsets.upload(lv.rings.offsets, stream);
      dev.ring_indices.upload(lv.rings.indices, stream);
      dev.ring_transpose.upload(lv.ring_transpose, stream);
      const std::vector<unsigned char> boundary(lv.boundary.begin(), lv.boundary.end());
      dev.boundary.upload(boundary, stream);
      check(cudaStreamSynchronize(stream), "level upload");
    }
    return dev;
  }

  // The graph of this frame's free set, built on the device.
  cuda::GraphView build_graph(const cuda::RingsView& rings, const unsigned char* active) {
    const std::size_t n = std::size_t(rings.num_vertices) + 1, r = std::max(rings.num_entries, 1);
    cuda::GraphBuildBuffers b;
    b.is_free = is_free.reserve(n);
    b.is_touched = is_touched.reserve(n);
    b.free_rank = free_rank.reserve(n);
    b.touched_rank = touched_rank.reserve(n);
    b.local = local.reserve(n);
    b.row_count = row_count.reserve(n);
    b.col_count = col_count.reserve(n);
    b.slot_entry = slot_entry.reserve(r);
    b.scan_scratch_bytes = cuda::graph_scan_scratch_bytes(rings.num_vertices);
    b.scan_scratch = scan_scratch.reserve(std::max<std::size_t>(b.scan_scratch_bytes, 1));
    b.global = global.reserve(n);
    b.row_offsets = row_offsets.reserve(n);
    b.row_cols = row_cols.reserve(r);
    b.row_slots = row_slots.reserve(r);
    b.row_vertices = row_vertices.reserve(r);
    b.col_offsets = col_offsets.reserve(n);
    b.col_rows = col_rows.reserve(r);
    b.col_entries = col_entries.reserve(r);
    b.inv_degree = inv_degree.reserve(n);
    b.counts = counts.reserve(2);
    cuda::launch_graph_build(rings, active, b, stream);
    cuda::GraphView v;
    v.num_vertices = rings.num_vertices;
    v.counts = b.counts;
    v.global = b.global;
    v.inv_degree = b.inv_degree;
    v.row_offsets = b.row_offsets;
    v.row_cols = b.row_cols;
    v.row_slots = b.row_slots;
    v.row_vertices = b.row_vertices;
    v.col_offsets = b.col_offsets;
    v.col_rows = b.col_rows;
    v.col_entries = b.col_entries;
    return v;
  }

  // Copies scalars [first, first + n) to the host and waits for them.
  const double* read_scalars(int first, int n) {
    double* host = readback.reserve(8);
    check(cudaMemcpyAsync(host, scalars.get() + first, n * sizeof(double), cudaMemcpyDeviceToHost, stream),
          "copy from the GPU");
    check(cudaStreamSynchronize(stream), "displacement solve");
    return host;
  }
  void clear_scalars(int first, int n) {
    check(cudaMemsetAsync(scalars.get() + first, 0, n * sizeof(double), stream), "cudaMemset");
  }
};

CudaDisplacementSolver::CudaDisplacementSolver() {
  require_cuda();
  state_ = std::make_unique<State>();
}

CudaDisplacementSolver::~CudaDisplacementSolver() = default;

DisplacementReport CudaDisplacementSolver::solve(const DisplacementProblem& problem, Eigen::VectorXf& d_level,
                                                 const DisplacementOptions& options) {
  const DisplacementOptions o = weights_in_centimetres(options);
  if (o.pcg_iterations > cuda::kMaxPcgIterations)
    throw std::invalid_argument("the CUDA displacement solve runs at most " + std::to_string(cuda::kMaxPcgIterations) +
                                " PCG iterations");
  const auto t0 = std::chrono::steady_clock::now();
  State& s = *state_;
  const cudaStream_t stream = s.stream;
  const MeshLevel& lv = *problem.level;
  const int n = lv.num_vertices;
  const std::size_t r = std::max<std::size_t>(lv.rings.indices.size(), 1);
  if (d_level.size() != n) d_level = Eigen::VectorXf::Zero(n);
  const LevelOnDevice& level_on_device = s.level(lv);
  const cuda::LevelView level = level_on_device.view();

  // The frame in: packed into page-locked memory, one copy.
  const bool has_prolonged = problem.prolonged.size() > 0, has_previous = problem.previous.size() > 0;
  const bool has_active = !problem.active.empty();
  const FrameLayout layout = frame_layout(n, has_prolonged, has_previous, has_active);
  unsigned char* staged = s.staging.reserve(layout.bytes);
  float* staged_floats = reinterpret_cast<float*>(staged);
  const auto stage = [&](std::size_t at, const float* from, std::size_t count) {
    std::memcpy(staged_floats + at, from, count * sizeof(float));
  };
  std::memcpy(staged, problem.lighting.data(), 9 * sizeof(double));
  stage(layout.base, problem.base.data(), 3 * n);
  stage(layout.normals, problem.base_normals.data(), 3 * n);
  stage(layout.albedo, problem.albedo.data(), 3 * n);
  stage(layout.colour, problem.samples->colour.data(), 3 * n);
  stage(layout.d, d_level.data(), n);
  if (has_prolonged) stage(layout.prolonged, problem.prolonged.data(), n);
  if (has_previous) stage(layout.previous, problem.previous.data(), n);
  for (int i = 0; i < n; ++i) staged[layout.visible + i] = problem.samples->visible[i] ? 1 : 0;
  if (has_active)
    for (int i = 0; i < n; ++i) staged[layout.active + i] = problem.active[i] ? 1 : 0;
  unsigned char* on_device = s.frame.reserve(layout.bytes);
  check(cudaMemcpyAsync(on_device, staged, layout.bytes, cudaMemcpyHostToDevice, stream), "copy to the GPU");
  const float* device_floats = reinterpret_cast<const float*>(on_device);
  cuda::FrameView frame;
  frame.base = device_floats + layout.base;
  frame.normals = device_floats + layout.normals;
  frame.albedo = device_floats + layout.albedo;
  frame.colour = device_floats + layout.colour;
  frame.visible = on_device + layout.visible;
  frame.lighting = reinterpret_cast<const double*>(on_device);
  frame.positions = s.positions.reserve(3 * n);
  check(cudaMemcpyAsync(frame.positions, frame.base, 3 * n * sizeof(float), cudaMemcpyDeviceToDevice, stream),
        "copy on the GPU");

  // The graph, then the unknowns and the regularisers' targets at the free
  // vertices. The fixed vertices' share of E_hier and E_temp (d = 0 there)
  // is a constant, kept so that the reported energies are the whole energy.
  const cuda::GraphView graph =
      s.build_graph(level_on_device.rings(), has_active ? on_device + layout.active : nullptr);
  double* scalars = s.scalars.reserve(cuda::kScalarCount);
  s.clear_scalars(0, cuda::kScalarCount);
  float* d = s.d.reserve(n);
  float* trial = s.trial.reserve(n);
  cuda::launch_gather_free(graph, s.is_free.get(), device_floats + layout.d, d, nullptr, 0, stream);
  float* prolonged = nullptr;
  float* previous = nullptr;
  if (has_prolonged) {
    prolonged = s.prolonged.reserve(n);
    cuda::launch_gather_free(graph, s.is_free.get(), device_floats + layout.prolonged, prolonged, scalars,
                             cuda::kProlongedFixed, stream);
  }
  if (has_previous) {
    previous = s.previous.reserve(n);
    cuda::launch_gather_free(graph, s.is_free.get(), device_floats + layout.previous, previous, scalars,
                             cuda::kPreviousFixed, stream);
  }
  cuda::Weights w;
  w.smooth = float(o.weights.smooth);
  w.hierarchy = float(o.weights.hierarchy);
  w.temporal = float(o.weights.temporal);
  w.coarse = float(o.weights.coarse);
  w.diag_const =
      float(o.weights.coarse + (has_previous ? o.weights.temporal : 0.0) + (has_prolonged ? o.weights.hierarchy : 0.0));
  cuda::NewtonVectors vectors;
  vectors.grad = s.grad.reserve(n);
  vectors.diag = s.diag.reserve(n);
  vectors.x = s.x.reserve(n);
  vectors.r = s.r.reserve(n);
  vectors.z = s.z.reserve(n);
  vectors.p = s.p.reserve(n);
  vectors.ap = s.ap.reserve(n);
  vectors.wgx = s.wgx.reserve(n);
  vectors.lx = s.lx.reserve(n);
  float* const x = vectors.x;
  float* const lx = vectors.lx;
  cuda::LinearisationView lin = s.lin[0].reserve(n, r), trial_lin = s.lin[1].reserve(n, r);
  const float huber = float(o.data_huber);

  // The trial point d + scale x and its energy, linearised there.
  const auto trial_into = [&](float scale) {
    cuda::launch_axpy(graph, d, scale, x, trial, stream);
    s.clear_scalars(cuda::kDataCost, 2);
    cuda::launch_displace(graph, frame, trial, stream);
    cuda::launch_linearise(graph, level, frame, trial_lin, huber, scalars, stream);
    cuda::launch_laplacian(graph, trial, lx, stream);
    cuda::launch_regulariser_cost(graph, w, trial, lx, prolonged, previous, scalars, stream);
  };
  double* host = s.readback.reserve(8);

  // One Gauss-Newton step up to the host's decision: its normal equations
  // solved (launch_newton_step), grad^T x for the predicted decrease, and
  // the full step's trial energy. One graph, one readback; captured again
  // only when what it holds changes.
  std::string signature;
  const auto sign = [&](const auto& value) { signature.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  sign(graph), sign(frame), sign(level), sign(lin), sign(trial_lin), sign(vectors), sign(w), sign(huber);
  sign(o.pcg_iterations), sign(d), sign(trial), sign(prolonged), sign(previous), sign(scalars), sign(host);
  State::CachedStep& step = s.steps[&lv];
  if (step.signature != signature) {
    step.graph.begin_capture(stream);
    s.clear_scalars(cuda::kGradDotStep, cuda::kScalarCount - cuda::kGradDotStep);
    check(cuda::launch_newton_step(graph, lin, w, vectors, d, prolonged, previous, scalars, o.pcg_iterations, stream),
          "cooperative launch of the Gauss-Newton step");
    trial_into(1.0f);
    check(cudaMemcpyAsync(host, scalars, (cuda::kGradDotStep + 1) * sizeof(double), cudaMemcpyDeviceToHost, stream),
          "copy from the GPU");
    step.graph.end_capture(stream);
    step.signature = std::move(signature);
  }
  // An accepted trial becomes the current point (copies, not a swap of
  // pointers: the graph holds these buffers).
  const auto accept_trial = [&] {
    const auto copy = [&](float* to, const float* from, std::size_t count) {
      check(cudaMemcpyAsync(to, from, count * sizeof(float), cudaMemcpyDeviceToDevice, stream), "copy on the GPU");
    };
    copy(d, trial, n);
    copy(lin.self, trial_lin.self, n);
    copy(lin.weight, trial_lin.weight, n);
    copy(lin.data_residual, trial_lin.data_residual, n);
    copy(lin.jac, trial_lin.jac, r);
    copy(lin.jac_by_column, trial_lin.jac_by_column, r);
  };

  // The energy at the start, linearised there (Solver::linearise and cost),
  // with the fixed shares of E_hier and E_temp.
  s.clear_scalars(cuda::kDataCost, 2);
  cuda::launch_displace(graph, frame, d, stream);
  cuda::launch_linearise(graph, level, frame, lin, huber, scalars, stream);
  cuda::launch_laplacian(graph, d, lx, stream);
  cuda::launch_regulariser_cost(graph, w, d, lx, prolonged, previous, scalars, stream);
  const double* start = s.read_scalars(cuda::kDataCost, 4);
  const double fixed_cost =
      o.weights.hierarchy * start[cuda::kProlongedFixed] + o.weights.temporal * start[cuda::kPreviousFixed];
  DisplacementReport rep;
  double current = start[cuda::kDataCost] + start[cuda::kRegulariserCost] + fixed_cost;
  rep.setup_ms = ms_since(t0);
  rep.initial_cost = current;
  for (rep.steps = 0; rep.steps < o.gauss_newton_steps; ++rep.steps) {
    step.graph.launch(stream);
    check(cudaStreamSynchronize(stream), "displacement solve");
    // The quadratic model's decrease, -grad^T x / 2 (see the CPU solver).
    const double predicted_decrease = -0.5 * host[cuda::kGradDotStep];
    if (predicted_decrease < o.function_tolerance * current) {
      rep.converged = true;
      break;
    }
    // Gauss-Newton step; halved if it does not lower the energy.
    double trial_cost = host[cuda::kDataCost] + host[cuda::kRegulariserCost] + fixed_cost;
    float scale = 0.5f;
    for (int h = 1; h < 4 && !(trial_cost < current); ++h, scale *= 0.5f) {
      trial_into(scale);
      const double* c = s.read_scalars(cuda::kDataCost, 2);
      trial_cost = c[0] + c[1] + fixed_cost;
    }
    if (!(trial_cost < current)) break;
    accept_trial();
    current = trial_cost;
  }
  rep.final_cost = current;

  // The result out.
  float* full = s.d_full.reserve(n);
  cuda::launch_scatter_free(graph, d, full, stream);
  check(cudaMemcpyAsync(d_level.data(), full, n * sizeof(float), cudaMemcpyDeviceToHost, stream), "copy from the GPU");
  check(cudaStreamSynchronize(stream), "displacement solve");
  return rep;
}

}  // namespace facecap
