#include "facecap/core/mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace facecap {

TriangleMesh triangulate(const std::vector<Polygon>& polygons, const std::vector<Vec2f>& uvs, int num_vertices) {
  TriangleMesh mesh;
  mesh.num_vertices = num_vertices;
  mesh.uvs = uvs;
  const bool has_uv = !uvs.empty();
  mesh.triangles.reserve(polygons.size() * 2);
  for (const Polygon& p : polygons) {
    mesh.triangles.push_back({p.v[0], p.v[1], p.v[2]});
    if (has_uv) mesh.triangle_uvs.push_back({p.uv[0], p.uv[1], p.uv[2]});
    if (p.size() == 4) {
      mesh.triangles.push_back({p.v[0], p.v[2], p.v[3]});
      if (has_uv) mesh.triangle_uvs.push_back({p.uv[0], p.uv[2], p.uv[3]});
    }
  }
  return mesh;
}

Positions vertex_normals(const Positions& positions, const std::vector<Triangle>& triangles) {
  Positions normals = Positions::Zero(3, positions.cols());
  for (const Triangle& t : triangles) {
    const Vec3f a = positions.col(t[0]);
    const Vec3f b = positions.col(t[1]);
    const Vec3f c = positions.col(t[2]);
    // (b - a) x (c - a) has length twice the area: the area weighting of §4.3.3.
    const Vec3f n = (b - a).cross(c - a);
    normals.col(t[0]) += n;
    normals.col(t[1]) += n;
    normals.col(t[2]) += n;
  }
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const float len = normals.col(i).norm();
    if (len > 0.0f) normals.col(i) /= len;
  }
  return normals;
}

VertexAdjacency vertex_adjacency(const std::vector<Triangle>& triangles, int num_vertices) {
  std::vector<std::vector<int>> rings(num_vertices);
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      rings[t[k]].push_back(t[(k + 1) % 3]);
      rings[t[k]].push_back(t[(k + 2) % 3]);
    }
  }
  VertexAdjacency adj;
  adj.offsets.resize(num_vertices + 1, 0);
  for (int i = 0; i < num_vertices; ++i) {
    auto& r = rings[i];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    adj.offsets[i + 1] = adj.offsets[i] + static_cast<int>(r.size());
  }
  adj.indices.reserve(adj.offsets.back());
  for (const auto& r : rings) adj.indices.insert(adj.indices.end(), r.begin(), r.end());
  return adj;
}

std::vector<bool> boundary_vertices(const std::vector<Triangle>& triangles, int num_vertices) {
  // Every triangle's edges as sorted keys (lower vertex in the high half);
  // an edge listed once is on the boundary.
  std::vector<uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<uint32_t>(t[k]), b = static_cast<uint32_t>(t[(k + 1) % 3]);
      edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<bool> boundary(num_vertices, false);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary[edges[i] >> 32] = boundary[edges[i] & 0xffffffffu] = true;
    i = j;
  }
  return boundary;
}

std::vector<std::vector<int>> boundary_loops(const std::vector<Triangle>& triangles) {
  // The directed edges whose reverse no triangle has: each boundary edge
  // once, in its triangle's winding.
  std::vector<std::pair<int, int>> directed;
  directed.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) directed.emplace_back(t[k], t[(k + 1) % 3]);
  std::sort(directed.begin(), directed.end());
  std::vector<std::pair<int, int>> boundary;
  for (const auto& [a, b] : directed)
    if (!std::binary_search(directed.begin(), directed.end(), std::pair{b, a})) boundary.emplace_back(a, b);
  // Walk them: from each unused edge, the next edge out of its end.
  std::vector<bool> used(boundary.size(), false);
  auto next_from = [&](int v) -> int {
    auto it = std::lower_bound(boundary.begin(), boundary.end(), std::pair{v, std::numeric_limits<int>::min()});
    for (; it != boundary.end() && it->first == v; ++it)
      if (!used[size_t(it - boundary.begin())]) return int(it - boundary.begin());
    return -1;
  };
  std::vector<std::vector<int>> loops;
  for (size_t start = 0; start < boundary.size(); ++start) {
    if (used[start]) continue;
    std::vector<int> loop;
    for (int e = int(start); e >= 0; e = next_from(boundary[size_t(e)].second)) {
      used[size_t(e)] = true;
      loop.push_back(boundary[size_t(e)].first);
      if (boundary[size_t(e)].second == loop.front()) break;
    }
    loops.push_back(std::move(loop));
  }
  std::stable_sort(loops.begin(), loops.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return loops;
}

std::vector<Vec2f> per_vertex_uvs(const TriangleMesh& mesh) {
  std::vector<Vec2f> out(mesh.num_vertices, Vec2f::Zero());
  std::vector<bool> set(mesh.num_vertices, false);
  for (size_t t = 0; t < mesh.triangle_uvs.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      if (!set[v]) {
        out[v] = mesh.uvs[mesh.triangle_uvs[t][k]];
        set[v] = true;
      }
    }
  }
  return out;
}

}  // namespace facecap
