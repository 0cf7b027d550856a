#pragma once
// The mesh hierarchy of §4.2 (Algorithm 1): levels M0 (the coarse face mesh)
// to Mk built by adaptive 4-8 subdivision.
//
// 4-8 subdivision of a triangulated quad mesh is newest-vertex bisection:
// each quad's diagonal is the "interior edge" of its two (mate) triangles;
// bisecting it inserts a vertex and makes the quad's sides the interior edges
// of the four children. A triangle whose mate is at a coarser generation
// first has its mate bisected (the `while f.mate.level < f.level` loop of
// Algorithm 1), so the mesh never cracks. Lone triangles (ICT has 548 outside
// the face) take their longest edge as the interior edge.
//
// One hierarchy level is two bisection generations (edges halve, four times
// the vertices), matching an image pyramid that halves the resolution per
// level. Triangles whose interior edge projects shorter than epsilon pixels in
// the first frame are not bisected (adaptivity). New vertices come from the
// 4-8 face mask: the mean of the block's four vertices (the edge midpoint on
// the boundary); old vertices keep their positions (the interpolating
// variant), so every level passes through the coarse mesh. UVs, albedo and
// displacements are prolonged with the same stencils.
#include <array>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"

namespace facecap {

// How a vertex created at some level is computed from earlier vertices.
struct VertexStencil {
  std::array<int, 4> parents{-1, -1, -1, -1};
  std::array<float, 4> weights{0, 0, 0, 0};
  int size = 0;
};

struct MeshLevel {
  int num_vertices = 0;
  std::vector<Triangle> triangles;          // counter-clockwise seen from outside
  std::vector<VertexStencil> new_vertices;  // vertices [previous level's count, num_vertices)
  VertexAdjacency rings;                    // one-ring neighbours
  // Incident triangles of each vertex as the other two corners in
  // counter-clockwise order, in compressed rows like `rings`.
  std::vector<int> corner_offsets;
  std::vector<std::array<int, 2>> corners;
  std::vector<std::array<int, 2>> corner_slots;  // where each corner vertex sits in the vertex's ring
  // For ring entry s (vertex i, neighbour j): the index of the entry (j, i)
  // in `rings.indices`, or -1 where j does not list i.
  std::vector<int> ring_transpose;
  std::vector<bool> boundary;
};

struct HierarchyOptions {
  int levels = 0;  // 0: choose from the projected edge length
  int max_levels = 4;
  double epsilon_px = 1.5;  // do not bisect interior edges shorter than this (full-resolution pixels)
  // Vertex positions for new vertices: the linear 4-8 mask (edge midpoint),
  // so that every level's base surface is the tracked coarse surface itself
  // and displacements are the detail relative to it (M_d = M + d N), or the
  // smoothing face mask (mean of the block's four vertices).
  bool smoothing_mask = false;
};

class MeshHierarchy {
 public:
  MeshHierarchy() = default;
  // Builds the levels from a triangulated quad mesh (per-polygon input so the
  // quads' diagonals are known) and its camera-space positions in the first frame.
  static MeshHierarchy build(const std::vector<Polygon>& polygons, int num_vertices, const Positions& first_frame,
                             const PinholeCamera& camera, const HierarchyOptions& options = {});

  int num_levels() const { return static_cast<int>(levels_.size()); }
  const MeshLevel& level(int l) const { return levels_[l]; }
  int vertices(int l) const { return levels_[l].num_vertices; }

  // Values at level l (rows: attribute dimensions) from values at level l - 1.
  Eigen::MatrixXf prolong(const Eigen::MatrixXf& coarser, int level) const;
  // From level 0 straight to level l.
  Eigen::MatrixXf prolong_from_coarse(const Eigen::MatrixXf& coarse, int level) const;
  // A vertex mask at level l: a new vertex is in it when all its stencil parents are.
  std::vector<bool> prolong_mask(const std::vector<bool>& coarse, int level) const;

 private:
  std::vector<MeshLevel> levels_;
};

// Level l as a mesh with UVs: each vertex's UV prolonged from the coarse
// mesh's per-vertex UVs (per_vertex_uvs) with the level's stencils, one UV
// per vertex (ICT's face region has no UV seam: where a vertex lists two UVs
// they are equal).
TriangleMesh level_uv_mesh(const MeshHierarchy& hierarchy, int level, const std::vector<Vec2f>& coarse_uvs);

// Area-weighted vertex normals from the level's corner lists (eq. 4.11 with d = 0).
Positions level_normals(const MeshLevel& level, const Positions& positions);

}  // namespace facecap
