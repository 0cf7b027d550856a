#pragma once
// A mesh for UV-grid tests: two triangles covering UV [0, 1]^2, its
// vertices at the UV corners.
#include "facecap/core/mesh.hpp"

namespace facecap::test {

inline TriangleMesh unit_square() {
  TriangleMesh m;
  m.num_vertices = 4;
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.triangle_uvs = m.triangles;
  return m;
}

}  // namespace facecap::test
