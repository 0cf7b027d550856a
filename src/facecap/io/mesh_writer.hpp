#pragma once
// Wavefront OBJ output (positions, UVs, quads and triangles), written
// atomically, for Blender, three.js and other tools.
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

struct ObjMesh {
  const Positions* positions = nullptr;            // 3 x N
  const std::vector<Polygon>* polygons = nullptr;  // vertex indices into positions, UV indices into uvs
  const std::vector<Vec2f>* uvs = nullptr;         // may be null
  std::string comment;                             // written as '# ...' lines at the top
};

void write_obj(const std::filesystem::path& path, const ObjMesh& mesh);

}  // namespace facecap
