#pragma once
// The displacement solve's own numbering of a hierarchy level (§4.3.4), as
// the CPU solver builds it (the CUDA backend builds the same rows and columns
// on the GPU: cuda/displacement_graph_kernels.cuh). Only the free vertices are unknowns, and only
// the residuals of free vertices and of their rings depend on them, so every
// pass runs over those "touched" vertices in a compact index space: free ones
// first, [0, num_free), then the rest of the touched, [num_free, touched).
// A vector of unknowns has `num_free` entries; d is zero everywhere else.
#include <vector>

#include "facecap/refine/displacement_solver.hpp"

namespace facecap {

struct DisplacementGraph {
  int num_free = 0;
  std::vector<int> global;        // local -> level vertex
  std::vector<float> inv_degree;  // 1 / ring size (0 for an isolated vertex)
  // Rows, per touched vertex: its free ring neighbours (local indices) and
  // their slot in the level's ring. Other neighbours multiply a zero.
  std::vector<int> row_offsets, row_cols, row_slots;
  std::vector<int> row_vertices;  // the level vertex of each row entry's column (global[row_cols[k]])
  // Columns, per free vertex q: its ring neighbours t (local, all touched) and
  // the row entry (t, q), or -1 where t's ring does not list q.
  std::vector<int> col_offsets, col_rows, col_entries;

  DisplacementGraph(const MeshLevel& level, const std::vector<int>& free_vertices);
  int touched() const { return static_cast<int>(global.size()); }
};

// Dirichlet: d = 0 on the level's boundary and outside the problem's active
// set; the rest are the unknowns.
std::vector<int> free_vertices(const DisplacementProblem& problem);

// The options with the regularisers' weights for d in centimetres (each
// divided by the square of `length_unit_cm`).
DisplacementOptions weights_in_centimetres(DisplacementOptions options);

// The most ring neighbours a vertex's Jacobian row holds; a vertex with more
// (none on a 4-8 hierarchy, whose valences stay below 12) gets zero
// derivatives for the extra ones.
constexpr int kMaxDisplacementRing = 32;

}  // namespace facecap
