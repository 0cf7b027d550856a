#pragma once
// DisplacementGraph (displacement_graph.hpp) built on the GPU from the
// level's resident rings and the frame's free set, so that a frame uploads a
// mask instead of the graph. The free vertices are numbered in vertex order
// as on the CPU; the other touched ones follow in vertex order (the CPU
// numbers them in the order it meets them, which changes no sum: every row
// and column keeps the ring order).
#include <cuda_runtime.h>

#include <cstddef>

#include "facecap/refine/cuda/displacement_kernels.cuh"

namespace facecap::cuda {

struct RingsView {
  int num_vertices = 0, num_entries = 0;
  const int* offsets = nullptr;    // num_vertices + 1
  const int* indices = nullptr;    // num_entries
  const int* transpose = nullptr;  // num_entries: the entry (j, i) of entry (i, j), or -1
  const unsigned char* boundary = nullptr;
};

// Device scratch and outputs, each sized for the level (num_vertices + 1 or
// num_entries): the caller allocates them with graph_scratch_bytes.
struct GraphBuildBuffers {
  int *is_free = nullptr, *is_touched = nullptr, *free_rank = nullptr, *touched_rank = nullptr, *local = nullptr;
  int *row_count = nullptr, *col_count = nullptr, *slot_entry = nullptr;
  void* scan_scratch = nullptr;
  std::size_t scan_scratch_bytes = 0;
  // The graph (GraphView points at these).
  int *global = nullptr, *row_offsets = nullptr, *row_cols = nullptr, *row_slots = nullptr, *row_vertices = nullptr;
  int *col_offsets = nullptr, *col_rows = nullptr, *col_entries = nullptr;
  float* inv_degree = nullptr;
  int* counts = nullptr;  // 2 ints: the free and the touched vertices
};

// Scratch bytes of the prefix sums over up to n + 1 elements.
std::size_t graph_scan_scratch_bytes(int n);

// Classifies and numbers the vertices (active may be null: all but the
// boundary are free), then builds the rows and columns; the sizes stay on
// the device (b.counts).
void launch_graph_build(const RingsView& rings, const unsigned char* active, const GraphBuildBuffers& b,
                        cudaStream_t s);

// out[a] = full[global[a]] over the free vertices, and scalars[slot] += the
// squares of `full` at the vertices that are not free (its fixed share).
void launch_gather_free(const GraphView& g, const int* is_free, const float* full, float* out, double* scalars,
                        int slot, cudaStream_t s);
// full = 0 and full[global[a]] = d[a].
void launch_scatter_free(const GraphView& g, const float* d, float* full, cudaStream_t s);

}  // namespace facecap::cuda
