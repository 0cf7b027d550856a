#pragma once
// Which surface point each texel of a UV texture stands for: the triangle
// covering the texel in the mesh's UV layout (per-corner UVs, v up as in
// OBJ) and the texel's barycentric weights in it. Built once per mesh; then
// baking a per-vertex attribute, or sampling an image at the surface points
// a texture holds, is a lookup per texel.
#include <vector>

#include "facecap/core/mesh.hpp"
#include "facecap/core/uv_texel.hpp"

namespace facecap {

struct UvTexelMap {
  int size = 0;                // the texture is size x size
  std::vector<int> triangle;   // per texel (row-major, row 0 = v 1); -1 where no triangle covers it
  std::vector<Vec3f> weights;  // barycentric weights of the triangle's three corners

  int index(int x, int y) const { return y * size + x; }
  // The per-vertex attribute (3 x N) at a covered texel.
  Vec3f interpolate(const std::vector<Triangle>& triangles, const Positions& attribute, int texel) const {
    const Triangle& t = triangles[triangle[texel]];
    const Vec3f& w = weights[texel];
    return w[0] * attribute.col(t[0]) + w[1] * attribute.col(t[1]) + w[2] * attribute.col(t[2]);
  }
};

UvTexelMap rasterize_uv(const TriangleMesh& mesh, int size);

// Millimetres on the surface per unit of UV, over all triangle edges of
// `mesh` with `shape` (cm) as its positions.
double millimetres_per_uv(const TriangleMesh& mesh, const Positions& shape);

// A texel map of about `texel_mm` millimetres of surface per texel, on a
// mesh of `mm_per_uv` millimetres per unit of UV (millimetres_per_uv()),
// between 32 and 1024 texels square; and its texels per millimetre.
struct MillimetreGrid {
  UvTexelMap map;
  double texels_per_mm = 0;
};
// Throws facecap::Error unless mm_per_uv and texel_mm are positive.
MillimetreGrid millimetre_grid(const TriangleMesh& mesh, double mm_per_uv, double texel_mm);

}  // namespace facecap
