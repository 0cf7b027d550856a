#include "facecap/refine/mesh_hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <type_traits>
#include <unordered_map>

#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<uint64_t>(std::min(a, b)), hi = static_cast<uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// Newest-vertex bisection on a growing triangle set.
class Bisector {
 public:
  struct Tri {
    std::array<int, 3> v;  // v[0] apex; interior edge (v[1], v[2]); counter-clockwise
    int generation = 0;
    bool alive = true;
  };

  Bisector(std::vector<Tri> tris, std::vector<Vec3f> positions, const PinholeCamera& cam, double epsilon,
           bool smoothing)
      : tris_(std::move(tris)), pos_(std::move(positions)), cam_(cam), epsilon_(epsilon), smoothing_(smoothing) {
    for (int t = 0; t < static_cast<int>(tris_.size()); ++t) add_edges(t);
  }

  // Bisects every live triangle below `generation` whose interior edge is
  // long enough, with the mates it needs, until nothing changes.
  void refine_to(int generation, std::vector<VertexStencil>& stencils) {
    bool changed = true;
    while (changed) {
      changed = false;
      const int count = static_cast<int>(tris_.size());
      for (int t = 0; t < count; ++t) {
        if (!tris_[t].alive || tris_[t].generation >= generation) continue;
        if (projected_length(tris_[t]) <= epsilon_) continue;
        bisect(t, stencils);
        changed = true;
      }
    }
  }

  int num_vertices() const { return static_cast<int>(pos_.size()); }
  std::vector<Triangle> live() const {
    std::vector<Triangle> out;
    for (const Tri& t : tris_)
      if (t.alive) out.push_back({t.v[0], t.v[1], t.v[2]});
    return out;
  }

 private:
  double projected_length(const Tri& t) const {
    const Vec3f& a = pos_[t.v[1]];
    const Vec3f& b = pos_[t.v[2]];
    if (a.z() <= 0 || b.z() <= 0) return 0.0;
    return (cam_.project(a) - cam_.project(b)).norm();
  }

  // Each edge maps to the (at most two) live triangles that use it.
  void add_edges(int t) {
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] =
          edges_.try_emplace(edge_key(tris_[t].v[k], tris_[t].v[(k + 1) % 3]), std::array<int, 2>{-1, -1});
      auto& slot = it->second;
      if (slot[0] < 0) {
        slot[0] = t;
      } else {
        slot[1] = t;
      }
    }
  }
  void remove_edges(int t) {
    for (int k = 0; k < 3; ++k) {
      auto& slot = edges_.at(edge_key(tris_[t].v[k], tris_[t].v[(k + 1) % 3]));
      if (slot[0] == t) {
        slot[0] = slot[1];
        slot[1] = -1;
      } else if (slot[1] == t) {
        slot[1] = -1;
      }
    }
  }
  int other(int t, int a, int b) const {
    const auto it = edges_.find(edge_key(a, b));
    if (it == edges_.end()) return -1;
    return it->second[0] == t ? it->second[1] : it->second[0];
  }
  bool interior_edge_is(const Tri& t, int a, int b) const {
    return (t.v[1] == a && t.v[2] == b) || (t.v[1] == b && t.v[2] == a);
  }

  void bisect(int t, std::vector<VertexStencil>& stencils) {
    const int b = tris_[t].v[1], c = tris_[t].v[2];
    int mate = other(t, b, c);
    // Algorithm 1, lines 5-7: the mate must share the interior edge first.
    while (mate >= 0 && !interior_edge_is(tris_[mate], b, c)) {
      bisect(mate, stencils);
      mate = other(t, b, c);
    }
    const int a = tris_[t].v[0];
    // The new vertex: the edge midpoint, or the smoothing face mask (the mean
    // of the block's four vertices) where the edge has a mate.
    VertexStencil s;
    if (mate >= 0 && smoothing_) {
      const int d = tris_[mate].v[0];
      s.parents = {b, c, a, d};
      s.weights = {0.25f, 0.25f, 0.25f, 0.25f};
      s.size = 4;
    } else {
      s.parents = {b, c, -1, -1};
      s.weights = {0.5f, 0.5f, 0, 0};
      s.size = 2;
    }
    Vec3f p = Vec3f::Zero();
    for (int k = 0; k < s.size; ++k) p += s.weights[k] * pos_[s.parents[k]];
    const int m = static_cast<int>(pos_.size());
    pos_.push_back(p);
    stencils.push_back(s);

    // Children: apex m, interior edges the parent's other two edges.
    auto split = [&](int tri) {
      const auto [apex, e1, e2] = tris_[tri].v;
      const int gen = tris_[tri].generation + 1;
      remove_edges(tri);
      tris_[tri].alive = false;
      tris_.push_back({{m, apex, e1}, gen, true});
      add_edges(static_cast<int>(tris_.size()) - 1);
      tris_.push_back({{m, e2, apex}, gen, true});
      add_edges(static_cast<int>(tris_.size()) - 1);
    };
    split(t);
    if (mate >= 0) split(mate);
  }

  std::vector<Tri> tris_;
  std::vector<Vec3f> pos_;
  PinholeCamera cam_;
  double epsilon_;
  bool smoothing_;
  std::unordered_map<uint64_t, std::array<int, 2>> edges_;
};

void finish_topology(MeshLevel& level) {
  level.rings = vertex_adjacency(level.triangles, level.num_vertices);
  level.boundary = boundary_vertices(level.triangles, level.num_vertices);
  std::vector<int> count(level.num_vertices + 1, 0);
  for (const Triangle& t : level.triangles)
    for (int v : t) ++count[v + 1];
  level.corner_offsets.assign(level.num_vertices + 1, 0);
  for (int i = 0; i < level.num_vertices; ++i) level.corner_offsets[i + 1] = level.corner_offsets[i] + count[i + 1];
  level.corners.resize(level.corner_offsets.back());
  std::vector<int> fill(level.corner_offsets.begin(), level.corner_offsets.end() - 1);
  for (const Triangle& t : level.triangles) {
    for (int k = 0; k < 3; ++k) level.corners[fill[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  }
  const VertexAdjacency& r = level.rings;
  auto slot_of = [&](int i, int v) {
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s)
      if (r.indices[s] == v) return s - r.offsets[i];
    return -1;
  };
  level.corner_slots.resize(level.corners.size());
  for (int i = 0; i < level.num_vertices; ++i) {
    for (int c = level.corner_offsets[i]; c < level.corner_offsets[i + 1]; ++c) {
      level.corner_slots[c] = {slot_of(i, level.corners[c][0]), slot_of(i, level.corners[c][1])};
    }
  }
  level.ring_transpose.resize(r.indices.size());
  for (int i = 0; i < level.num_vertices; ++i) {
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
      const int j = r.indices[s];
      const int slot = slot_of(j, i);
      level.ring_transpose[s] = slot >= 0 ? r.offsets[j] + slot : -1;
    }
  }
}

}  // namespace

MeshHierarchy MeshHierarchy::build(const std::vector<Polygon>& polygons, int num_vertices, const Positions& first,
                                   const PinholeCamera& camera, const HierarchyOptions& options) {
  if (first.cols() != num_vertices) throw Error("mesh hierarchy: positions do not match the vertex count");
  std::vector<Bisector::Tri> tris;
  std::vector<Vec3f> positions(num_vertices);
  for (int i = 0; i < num_vertices; ++i) positions[i] = first.col(i);
  double edge_sum = 0;
  int edge_count = 0;
  for (const Polygon& p : polygons) {
    if (p.size() == 4) {
      // Diagonal (v0, v2) is the interior edge of both halves: they are mates.
      tris.push_back({{p.v[1], p.v[2], p.v[0]}, 0, true});
      tris.push_back({{p.v[3], p.v[0], p.v[2]}, 0, true});
    } else {
      // Lone triangle: its longest edge is the interior edge.
      int best = 0;
      float longest = -1;
      for (int k = 0; k < 3; ++k) {
        const float len = (positions[p.v[(k + 1) % 3]] - positions[p.v[(k + 2) % 3]]).norm();
        if (len > longest) longest = len, best = k;
      }
      tris.push_back({{p.v[best], p.v[(best + 1) % 3], p.v[(best + 2) % 3]}, 0, true});
    }
    const Vec3f& a = positions[p.v[0]];
    const Vec3f& b = positions[p.v[1]];
    if (a.z() > 0 && b.z() > 0) {
      edge_sum += (camera.project(a) - camera.project(b)).norm();
      ++edge_count;
    }
  }
  int levels = options.levels;
  if (levels <= 0) {
    // Halve the edges per level until they project at about epsilon.
    const double edge = edge_count > 0 ? edge_sum / edge_count : 1.0;
    levels = 1 + std::max(0, static_cast<int>(std::floor(std::log2(std::max(1.0, edge / options.epsilon_px)))));
  }
  levels = std::clamp(levels, 1, options.max_levels);

  MeshHierarchy h;
  Bisector bisector(std::move(tris), std::move(positions), camera, options.epsilon_px, options.smoothing_mask);
  MeshLevel base;
  base.num_vertices = num_vertices;
  base.triangles = bisector.live();
  finish_topology(base);
  h.levels_.push_back(std::move(base));
  for (int l = 1; l < levels; ++l) {
    MeshLevel level;
    bisector.refine_to(2 * l, level.new_vertices);
    level.num_vertices = bisector.num_vertices();
    level.triangles = bisector.live();
    finish_topology(level);
    h.levels_.push_back(std::move(level));
  }
  return h;
}

Eigen::MatrixXf MeshHierarchy::prolong(const Eigen::MatrixXf& coarser, int l) const {
  const MeshLevel& level = levels_[l];
  const int before = levels_[l - 1].num_vertices;
  Eigen::MatrixXf out(coarser.rows(), level.num_vertices);
  out.leftCols(before) = coarser;
  // New vertices in order (a stencil may read earlier new vertices), on the
  // raw column-major data, with the common row counts (positions, scalars)
  // known at compile time.
  float* data = out.data();
  const auto fill = [&](auto rows_constant) {
    const int rows = rows_constant > 0 ? int(rows_constant) : int(out.rows());
    for (int v = before; v < level.num_vertices; ++v) {
      const VertexStencil& s = level.new_vertices[v - before];
      float* dst = data + size_t(v) * rows;
      for (int r = 0; r < rows; ++r) dst[r] = 0.0f;
      for (int k = 0; k < s.size; ++k) {
        const float* src = data + size_t(s.parents[k]) * rows;
        for (int r = 0; r < rows; ++r) dst[r] += s.weights[k] * src[r];
      }
    }
  };
  if (out.rows() == 3)
    fill(std::integral_constant<int, 3>{});
  else if (out.rows() == 1)
    fill(std::integral_constant<int, 1>{});
  else
    fill(std::integral_constant<int, 0>{});
  return out;
}

Eigen::MatrixXf MeshHierarchy::prolong_from_coarse(const Eigen::MatrixXf& coarse, int level) const {
  Eigen::MatrixXf values = coarse;
  for (int l = 1; l <= level; ++l) values = prolong(values, l);
  return values;
}

std::vector<bool> MeshHierarchy::prolong_mask(const std::vector<bool>& coarse, int level) const {
  std::vector<bool> mask = coarse;
  for (int l = 1; l <= level; ++l) {
    const MeshLevel& lv = levels_[l];
    const int before = levels_[l - 1].num_vertices;
    mask.resize(lv.num_vertices, false);
    for (int v = before; v < lv.num_vertices; ++v) {
      const VertexStencil& s = lv.new_vertices[v - before];
      bool in = true;
      for (int k = 0; k < s.size; ++k) in = in && mask[s.parents[k]];
      mask[v] = in;
    }
  }
  return mask;
}

TriangleMesh level_uv_mesh(const MeshHierarchy& hierarchy, int level, const std::vector<Vec2f>& coarse_uvs) {
  Eigen::MatrixXf coarse(2, Eigen::Index(coarse_uvs.size()));
  for (size_t i = 0; i < coarse_uvs.size(); ++i) coarse.col(Eigen::Index(i)) = coarse_uvs[i];
  const Eigen::MatrixXf fine = hierarchy.prolong_from_coarse(coarse, level);
  TriangleMesh mesh;
  mesh.num_vertices = int(fine.cols());
  mesh.triangles = hierarchy.level(level).triangles;
  mesh.triangle_uvs = mesh.triangles;
  mesh.uvs.resize(fine.cols());
  for (Eigen::Index i = 0; i < fine.cols(); ++i) mesh.uvs[i] = fine.col(i);
  return mesh;
}

Positions level_normals(const MeshLevel& level, const Positions& p) {
  Positions n(3, level.num_vertices);
  parallel_for(
      level.num_vertices,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          Vec3f m = Vec3f::Zero();
          const Vec3f pi = p.col(i);
          for (int c = level.corner_offsets[i]; c < level.corner_offsets[i + 1]; ++c) {
            const auto& [j, k] = level.corners[c];
            m += (p.col(j) - pi).cross(p.col(k) - pi);
          }
          const float len = m.norm();
          n.col(i) = len > 0 ? Vec3f(m / len) : Vec3f::Zero();
        }
      },
      4096);
  return n;
}

}  // namespace facecap
