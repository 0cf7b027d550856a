#pragma once
// Wavefront OBJ reader for the ICT model files, plain `.obj` or gzip `.obj.gz`
// (zlib reads both transparently). Reads `v`, `vt` and `f` records; ignores the rest.
#include <filesystem>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

struct ObjData {
  std::vector<float> positions;  // x y z per vertex
  std::vector<Vec2f> uvs;
  std::vector<Polygon> polygons;
  int num_vertices() const { return static_cast<int>(positions.size() / 3); }
};

struct ObjReadOptions {
  bool read_topology = true;  // false: only `v` records (blendshape targets)
};

// Throws facecap::Error naming the file when it is missing, unreadable,
// truncated or corrupt (bad gzip stream, malformed record, non-finite
// coordinate, face index out of range).
ObjData read_obj(const std::filesystem::path& path, const ObjReadOptions& options = {});

}  // namespace facecap
