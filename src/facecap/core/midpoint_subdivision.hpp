#pragma once
// Uniform 1-to-4 midpoint subdivision of a triangle mesh. Used to render the
// synthetic ground truth's fine wrinkles on a denser mesh than the model's.
// (The refinement's adaptive 4-8 hierarchy is a different scheme: refine/.)
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

struct MidpointSubdivision {
  int num_coarse = 0;
  int num_vertices = 0;                     // coarse vertices first, then one per split edge
  std::vector<std::array<int, 2>> parents;  // for vertices >= num_coarse: the two averaged vertices
  std::vector<Triangle> triangles;

  // Fine-level values of a per-vertex attribute (3 x num_coarse in, 3 x num_vertices out).
  Positions prolong(const Positions& coarse) const;
  std::vector<Vec2f> prolong(const std::vector<Vec2f>& coarse) const;
};

MidpointSubdivision subdivide_midpoint(const std::vector<Triangle>& triangles, int num_vertices, int levels);

}  // namespace facecap
