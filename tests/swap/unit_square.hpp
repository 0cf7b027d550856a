#pragma once
// A mesh for UV-grid tests: two triangles covering UV [0, 1]^2, its
// vertices at the UV corners; and the largest value of a grid.
#include <opencv2/core.hpp>

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

inline double largest(const cv::Mat& grid) {
  double hi = 0;
  cv::minMaxLoc(grid, nullptr, &hi);
  return hi;
}

}  // namespace facecap::test
