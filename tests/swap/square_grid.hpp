#pragma once
// A mesh for the swap's mesh tests: a square grid of (n + 1)^2 vertices, row
// by row, two triangles per cell.
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap::test {

inline std::vector<Triangle> square_grid(int n) {
  std::vector<Triangle> t;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  }
  return t;
}

}  // namespace facecap::test
