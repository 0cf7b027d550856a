#include "facecap/refine/displacement_graph.hpp"

namespace facecap {

DisplacementGraph::DisplacementGraph(const MeshLevel& lv, const std::vector<int>& free_vertices) {
  const int n = lv.num_vertices;
  const VertexAdjacency& r = lv.rings;
  std::vector<int> local(n, -1);
  num_free = static_cast<int>(free_vertices.size());
  for (int i : free_vertices) {
    local[i] = static_cast<int>(global.size());
    global.push_back(i);
  }
  for (int i : free_vertices)
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
      const int j = r.indices[s];
      if (local[j] < 0) {
        local[j] = static_cast<int>(global.size());
        global.push_back(j);
      }
    }
  const int nt = static_cast<int>(global.size());
  inv_degree.resize(nt);
  // Per level ring slot of a touched vertex: its row entry, or -1.
  std::vector<int> slot_entry(r.indices.size(), -1);
  row_offsets.assign(1, 0);
  for (int t = 0; t < nt; ++t) {
    const int i = global[t];
    inv_degree[t] = r.degree(i) > 0 ? 1.0f / float(r.degree(i)) : 0.0f;
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
      const int j = local[r.indices[s]];
      if (j < 0 || j >= num_free) continue;
      slot_entry[s] = static_cast<int>(row_cols.size());
      row_cols.push_back(j);
      row_slots.push_back(s - r.offsets[i]);
      row_vertices.push_back(r.indices[s]);
    }
    row_offsets.push_back(static_cast<int>(row_cols.size()));
  }
  col_offsets.assign(1, 0);
  for (int a = 0; a < num_free; ++a) {
    const int q = global[a];
    for (int s = r.offsets[q]; s < r.offsets[q + 1]; ++s) {
      const int back = lv.ring_transpose[s];
      col_rows.push_back(local[r.indices[s]]);
      col_entries.push_back(back >= 0 ? slot_entry[back] : -1);
    }
    col_offsets.push_back(static_cast<int>(col_rows.size()));
  }
}

std::vector<int> free_vertices(const DisplacementProblem& p) {
  std::vector<int> out;
  const MeshLevel& lv = *p.level;
  for (int i = 0; i < lv.num_vertices; ++i)
    if (!lv.boundary[i] && (p.active.empty() || p.active[i])) out.push_back(i);
  return out;
}

DisplacementOptions weights_in_centimetres(DisplacementOptions o) {
  const double k = 1.0 / (o.length_unit_cm * o.length_unit_cm);
  o.weights.smooth *= k;
  o.weights.hierarchy *= k;
  o.weights.temporal *= k;
  o.weights.coarse *= k;
  return o;
}

}  // namespace facecap
