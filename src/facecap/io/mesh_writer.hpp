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
  std::string comment = {};                        // written as '# ...' lines at the top
  // A material library beside the file (`mtllib`) and the material its faces
  // use (`usemtl`); empty: none.
  std::string material_library = {};
  std::string material = {};
};

void write_obj(const std::filesystem::path& path, const ObjMesh& mesh);

// A material library of one material, `name`, lit as a plain diffuse surface
// whose colour is the image `texture` (`map_Kd`, a path relative to the
// library's folder; empty: white): how an OBJ names its texture for Blender,
// MeshLab and three.js's MTLLoader.
void write_mtl(const std::filesystem::path& path, const std::string& name, const std::string& texture,
               const std::string& comment);

}  // namespace facecap
