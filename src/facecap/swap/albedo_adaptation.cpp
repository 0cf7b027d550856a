#include "facecap/swap/albedo_adaptation.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <map>
#include <numeric>

#include "facecap/core/error.hpp"
#include "facecap/core/statistics.hpp"

namespace facecap {

namespace {

// The vertices of the longest boundary loop: the face's outline, not the
// rims of the eye and mouth holes (whose target colours are the eyes and the
// mouth interior, not skin).
std::vector<bool> outer_boundary(const std::vector<Triangle>& triangles, int num_vertices) {
  std::map<std::pair<int, int>, int> edge_use;
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++edge_use[{std::min(a, b), std::max(a, b)}];
    }
  }
  // Union-find over the boundary edges.
  std::vector<int> parent(num_vertices);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> on(num_vertices, false);
  for (const auto& [edge, uses] : edge_use) {
    if (uses != 1) continue;
    on[edge.first] = on[edge.second] = true;
    parent[find(edge.first)] = find(edge.second);
  }
  std::vector<int> size(num_vertices, 0);
  for (int v = 0; v < num_vertices; ++v)
    if (on[v]) ++size[find(v)];
  const int largest = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<bool> outer(num_vertices, false);
  for (int v = 0; v < num_vertices; ++v) outer[v] = on[v] && find(v) == largest;
  return outer;
}

}  // namespace

struct AlbedoAdaptation::Impl {
  std::vector<int> interior;             // vertex -> row of the interior system, -1 on the boundary or unused
  std::vector<int> boundary;             // fixed vertices
  std::vector<bool> outline;             // used vertices on the outer boundary: fixed where known
  Eigen::SparseMatrix<double> coupling;  // interior x all: -adjacency to the fixed vertices
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  int used = 0;
};

AlbedoAdaptation::AlbedoAdaptation(const std::vector<Triangle>& triangles, int num_vertices,
                                   const std::vector<bool>& target_known)
    : impl_(std::make_unique<Impl>()) {
  const VertexAdjacency adj = vertex_adjacency(triangles, num_vertices);
  const std::vector<bool> on_boundary = outer_boundary(triangles, num_vertices);
  Impl& m = *impl_;
  m.interior.assign(num_vertices, -1);
  m.outline.assign(num_vertices, false);
  std::vector<bool> fixed(num_vertices, false);
  int rows = 0;
  for (int v = 0; v < num_vertices; ++v) {
    if (adj.degree(v) == 0) continue;
    m.outline[v] = on_boundary[v];
    if (on_boundary[v] && target_known[v]) {
      fixed[v] = true;
      m.boundary.push_back(v);
    } else {
      m.interior[v] = rows++;
    }
  }
  if (m.boundary.empty()) throw Error("albedo adaptation: no boundary vertex of the face was seen in the target");
  std::vector<Eigen::Triplet<double>> a, c;
  for (int v = 0; v < num_vertices; ++v) {
    const int r = m.interior[v];
    if (r < 0) continue;
    a.emplace_back(r, r, adj.degree(v));
    for (int k = adj.offsets[v]; k < adj.offsets[v + 1]; ++k) {
      const int u = adj.indices[k];
      if (m.interior[u] >= 0)
        a.emplace_back(r, m.interior[u], -1.0);
      else if (fixed[u])
        c.emplace_back(r, u, 1.0);
    }
  }
  Eigen::SparseMatrix<double> lap(rows, rows);
  lap.setFromTriplets(a.begin(), a.end());
  m.coupling.resize(rows, num_vertices);
  m.coupling.setFromTriplets(c.begin(), c.end());
  // A component without a fixed vertex would make L singular: a tiny ridge
  // pins its offset to zero instead.
  for (int r = 0; r < rows; ++r) lap.coeffRef(r, r) += 1e-6;
  m.solver.compute(lap);
  if (m.solver.info() != Eigen::Success) throw Error("albedo adaptation: the mesh Laplacian could not be factorised");
  m.used = rows;
}

AlbedoAdaptation::~AlbedoAdaptation() = default;
AlbedoAdaptation::AlbedoAdaptation(AlbedoAdaptation&&) noexcept = default;
AlbedoAdaptation& AlbedoAdaptation::operator=(AlbedoAdaptation&&) noexcept = default;

int AlbedoAdaptation::boundary_count() const { return static_cast<int>(impl_->boundary.size()); }

bool AlbedoAdaptation::fixes_the_same(const std::vector<bool>& target_known) const {
  const Impl& m = *impl_;
  if (target_known.size() != m.outline.size()) return false;
  // m.boundary lists the fixed vertices in order: the same list, or not.
  size_t k = 0;
  for (size_t v = 0; v < m.outline.size(); ++v) {
    if (!(m.outline[v] && target_known[v])) continue;
    if (k == m.boundary.size() || m.boundary[k] != int(v)) return false;
    ++k;
  }
  return k == m.boundary.size();
}

Positions AlbedoAdaptation::offset(const Positions& source, const Positions& target) const {
  const Impl& m = *impl_;
  const int n = static_cast<int>(source.cols());
  Positions h = Positions::Zero(3, n);
  for (int v : m.boundary) h.col(v) = target.col(v) - source.col(v);
  // Robust boundary: a boundary vertex whose offset is far from the others'
  // (hair, a collar, a hand the target's outline crosses) takes their median.
  for (int c = 0; c < 3; ++c) {
    std::vector<float> values;
    for (int v : m.boundary) values.push_back(h(c, v));
    const float mid = median_in_place(values);
    for (float& x : values) x = std::abs(x - mid);
    const float spread = 1.4826f * median_in_place(values) + 1e-3f;  // MAD as a standard deviation
    for (int v : m.boundary) {
      if (std::abs(h(c, v) - mid) > 2.5f * spread) h(c, v) = mid;
    }
  }
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd fixed_values = h.row(c).transpose().cast<double>();
    const Eigen::VectorXd rhs = m.coupling * fixed_values;  // L_ii h_i = -L_ib h_b = A_ib h_b
    const Eigen::VectorXd x = m.solver.solve(rhs);
    for (int v = 0; v < n; ++v) {
      if (m.interior[v] >= 0) h(c, v) = static_cast<float>(x[m.interior[v]]);
    }
  }
  return h;
}

}  // namespace facecap
