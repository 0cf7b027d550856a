#pragma once
// Polygon topology of the face model and the triangle meshes derived from it.
#include <array>
#include <vector>

#include "facecap/core/geometry.hpp"

namespace facecap {

// A quad or triangle of the source model; corner 3 is -1 for triangles.
// uv[k] indexes the UV table (UVs are per corner: seams split them).
struct Polygon {
  std::array<int, 4> v{-1, -1, -1, -1};
  std::array<int, 4> uv{-1, -1, -1, -1};
  int size() const { return v[3] < 0 ? 3 : 4; }
};

using Triangle = std::array<int, 3>;

// Triangle mesh with per-corner UV indices (same shape as `triangles`).
struct TriangleMesh {
  std::vector<Triangle> triangles;
  std::vector<Triangle> triangle_uvs;  // empty when the mesh has no UVs
  std::vector<Vec2f> uvs;
  int num_vertices = 0;
};

// Splits each quad along its v0-v2 diagonal; keeps triangles as they are.
TriangleMesh triangulate(const std::vector<Polygon>& polygons, const std::vector<Vec2f>& uvs, int num_vertices);

// Area-weighted vertex normals (paper §4.3.3: n_i = sum over incident
// triangles of (v_j - v_i) x (v_k - v_i)), normalised; zero for unused vertices.
Positions vertex_normals(const Positions& positions, const std::vector<Triangle>& triangles);

// One-ring neighbours in compressed rows: neighbours of vertex i are
// indices[offsets[i] .. offsets[i+1]).
struct VertexAdjacency {
  std::vector<int> offsets;
  std::vector<int> indices;
  int degree(int i) const { return offsets[i + 1] - offsets[i]; }
};
VertexAdjacency vertex_adjacency(const std::vector<Triangle>& triangles, int num_vertices);

// Vertices on the open boundary of the triangle mesh (an edge used by one triangle).
std::vector<bool> boundary_vertices(const std::vector<Triangle>& triangles, int num_vertices);

// The open boundary as closed loops of vertices, each in the order of its
// triangles' winding (a hole's loop runs opposite to the outer one's), the
// longest first. A vertex where two loops touch starts or continues either.
std::vector<std::vector<int>> boundary_loops(const std::vector<Triangle>& triangles);

// One UV per vertex (the first corner that uses it), for per-vertex lookups.
std::vector<Vec2f> per_vertex_uvs(const TriangleMesh& mesh);

// The UV at barycentric weights `bary` (of corners 1 and 2; corner 0 has the
// rest) in triangle `triangle` of a mesh with UVs.
inline Vec2f uv_at(const TriangleMesh& mesh, int triangle, const Vec2f& bary) {
  const Triangle& corner = mesh.triangle_uvs[triangle];
  return (1 - bary.x() - bary.y()) * mesh.uvs[corner[0]] + bary.x() * mesh.uvs[corner[1]] +
         bary.y() * mesh.uvs[corner[2]];
}

}  // namespace facecap
