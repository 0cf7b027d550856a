#pragma once
// Binary PLY output (Stanford polygon format, version 1.0): positions, and
// per vertex optionally a normal, a colour and a UV, with quads and
// triangles as vertex lists. MeshLab, CloudCompare, Open3D and Blender read
// it with its colours, which OBJ has no standard place for. Binary, it is
// written without formatting numbers (a refined frame of 33k vertices in 5 ms
// against the OBJ's 26: bench/io_bench.cpp) and, normals and colours
// included, comes to half an OBJ's size (a third for a coarse frame).
// Written atomically.
//
// The header names the properties as those tools expect them: float x y z,
// float nx ny nz, uchar red green blue, float s t (the UV, with OBJ's
// origin at the image's bottom-left), and a face element's
// "list uchar int vertex_indices". The body is in the machine's byte order,
// which the header's format line says.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

struct PlyMesh {
  const Positions* positions = nullptr;            // 3 x N
  const std::vector<Polygon>* polygons = nullptr;  // vertex indices into positions (their UV indices unused)
  const Positions* normals = nullptr;              // 3 x N unit normals, or null
  const Positions* colours = nullptr;              // 3 x N RGB in [0, 1] (clamped, rounded to 8 bits), or null
  const std::vector<Vec2f>* uvs = nullptr;         // one per vertex, or null
  std::string comment;                             // one 'comment' header line per line
};

// Throws facecap::Error, writing nothing, where a face names a vertex that is
// not there, an attribute's count differs from the positions', or a value is
// not finite.
void write_ply(const std::filesystem::path& path, const PlyMesh& mesh);

}  // namespace facecap
