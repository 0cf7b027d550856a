#include <cub/device/device_scan.cuh>

#include "facecap/refine/cuda/block_reduce.cuh"
#include "facecap/refine/cuda/displacement_graph_kernels.cuh"

namespace facecap::cuda {

namespace {

constexpr int kThreads = kBlockThreads;
int blocks_for(int n) { return n > 0 ? (n + kThreads - 1) / kThreads : 1; }

__global__ void classify_kernel(RingsView r, const unsigned char* active, int* is_free, int* is_touched) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > r.num_vertices) return;
  // The extra element n is 0, so that the exclusive sums end with the totals.
  is_free[i] = i < r.num_vertices && !r.boundary[i] && (active == nullptr || active[i]) ? 1 : 0;
  is_touched[i] = 0;
}

// A vertex that is not free is touched when some free vertex lists it in its ring.
__global__ void touch_kernel(RingsView r, const int* is_free, int* is_touched) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= r.num_vertices || !is_free[i]) return;
  for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
    const int j = r.indices[s];
    if (!is_free[j]) is_touched[j] = 1;
  }
}

__global__ void number_kernel(RingsView r, GraphBuildBuffers b) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= r.num_vertices) return;
  const int num_free = b.free_rank[r.num_vertices];
  int local = -1;
  if (b.is_free[i])
    local = b.free_rank[i];
  else if (b.is_touched[i])
    local = num_free + b.touched_rank[i];
  b.local[i] = local;
  if (local >= 0) b.global[local] = i;
  if (i == 0) {
    b.counts[0] = num_free;
    b.counts[1] = num_free + b.touched_rank[r.num_vertices];
  }
}

// Per t in [0, n]: the row's free neighbours (0 past the touched) and the
// column's length (0 past the free), so that sums over n + 1 end with the totals.
__global__ void count_kernel(RingsView r, GraphBuildBuffers b) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t > r.num_vertices) return;
  const int num_free = b.counts[0], touched = b.counts[1];
  int free_neighbours = 0, degree = 0;
  if (t < touched) {
    const int i = b.global[t];
    degree = r.offsets[i + 1] - r.offsets[i];
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) free_neighbours += b.is_free[r.indices[s]];
    b.inv_degree[t] = degree > 0 ? 1.0f / float(degree) : 0.0f;
  }
  b.row_count[t] = free_neighbours;
  b.col_count[t] = t < num_free ? degree : 0;
}

__global__ void row_fill_kernel(RingsView r, GraphBuildBuffers b) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= b.counts[1]) return;
  const int i = b.global[t];
  int e = b.row_offsets[t];
  for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
    const int j = r.indices[s];
    if (!b.is_free[j]) continue;
    b.row_cols[e] = b.local[j];
    b.row_slots[e] = s - r.offsets[i];
    b.row_vertices[e] = j;
    b.slot_entry[s] = e;
    ++e;
  }
}

// Every ring neighbour t of a free vertex q is touched and lists q among its
// row's free neighbours, so slot_entry of (t, q) was written this frame.
__global__ void col_fill_kernel(RingsView r, GraphBuildBuffers b) {
  const int a = blockIdx.x * blockDim.x + threadIdx.x;
  if (a >= b.counts[0]) return;
  const int q = b.global[a];
  int k = b.col_offsets[a];
  for (int s = r.offsets[q]; s < r.offsets[q + 1]; ++s, ++k) {
    b.col_rows[k] = b.local[r.indices[s]];
    const int back = r.transpose[s];
    b.col_entries[k] = back >= 0 ? b.slot_entry[back] : -1;
  }
}

__global__ void gather_free_kernel(GraphView g, const int* is_free, const float* full, float* out, double* scalars,
                                   int slot) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < g.counts[0]) out[i] = full[g.global[i]];
  double fixed = 0;
  if (scalars && i < g.num_vertices && !is_free[i]) fixed = double(full[i]) * full[i];
  if (scalars) block_add(fixed, scalars + slot);
}

__global__ void scatter_free_kernel(GraphView g, const float* d, float* full) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < g.counts[0]) full[g.global[i]] = d[i];
}

}  // namespace

std::size_t graph_scan_scratch_bytes(int n) {
  std::size_t bytes = 0;
  cub::DeviceScan::ExclusiveSum(nullptr, bytes, static_cast<const int*>(nullptr), static_cast<int*>(nullptr), n + 1);
  return bytes;
}

void launch_graph_build(const RingsView& r, const unsigned char* active, const GraphBuildBuffers& b, cudaStream_t s) {
  const int n = r.num_vertices;
  classify_kernel<<<blocks_for(n + 1), kThreads, 0, s>>>(r, active, b.is_free, b.is_touched);
  touch_kernel<<<blocks_for(n), kThreads, 0, s>>>(r, b.is_free, b.is_touched);
  std::size_t bytes = b.scan_scratch_bytes;
  cub::DeviceScan::ExclusiveSum(b.scan_scratch, bytes, b.is_free, b.free_rank, n + 1, s);
  bytes = b.scan_scratch_bytes;
  cub::DeviceScan::ExclusiveSum(b.scan_scratch, bytes, b.is_touched, b.touched_rank, n + 1, s);
  number_kernel<<<blocks_for(n), kThreads, 0, s>>>(r, b);
  count_kernel<<<blocks_for(n + 1), kThreads, 0, s>>>(r, b);
  bytes = b.scan_scratch_bytes;
  cub::DeviceScan::ExclusiveSum(b.scan_scratch, bytes, b.row_count, b.row_offsets, n + 1, s);
  bytes = b.scan_scratch_bytes;
  cub::DeviceScan::ExclusiveSum(b.scan_scratch, bytes, b.col_count, b.col_offsets, n + 1, s);
  row_fill_kernel<<<blocks_for(n), kThreads, 0, s>>>(r, b);
  col_fill_kernel<<<blocks_for(n), kThreads, 0, s>>>(r, b);
}

void launch_gather_free(const GraphView& g, const int* is_free, const float* full, float* out, double* scalars,
                        int slot, cudaStream_t s) {
  gather_free_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, is_free, full, out, scalars, slot);
}

void launch_scatter_free(const GraphView& g, const float* d, float* full, cudaStream_t s) {
  cudaMemsetAsync(full, 0, g.num_vertices * sizeof(float), s);
  scatter_free_kernel<<<blocks_for(g.num_vertices), kThreads, 0, s>>>(g, d, full);
}

}  // namespace facecap::cuda
