#include "facecap/render/uv_raster.hpp"

#include <algorithm>
#include <cmath>

#include "facecap/core/error.hpp"

namespace facecap {

UvTexelMap rasterize_uv(const TriangleMesh& mesh, int size) {
  UvTexelMap map;
  map.size = size;
  map.triangle.assign(size_t(size) * size, -1);
  map.weights.assign(size_t(size) * size, Vec3f::Zero());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    Vec2f p[3];
    for (int k = 0; k < 3; ++k) p[k] = uv_to_texel(mesh.uvs[mesh.triangle_uvs[t][k]], size);
    const float area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
    if (std::abs(area) < 1e-8f) continue;
    const int x0 = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(size - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(size - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const float w0 = ((p[1].x() - x) * (p[2].y() - y) - (p[1].y() - y) * (p[2].x() - x)) / area;
        const float w1 = ((p[2].x() - x) * (p[0].y() - y) - (p[2].y() - y) * (p[0].x() - x)) / area;
        const float w2 = 1.0f - w0 - w1;
        if (w0 < -1e-4f || w1 < -1e-4f || w2 < -1e-4f) continue;
        const int i = map.index(x, y);
        map.triangle[i] = static_cast<int>(t);
        map.weights[i] = Vec3f(w0, w1, w2);
      }
    }
  }
  return map;
}

double millimetres_per_uv(const TriangleMesh& mesh, const Positions& shape) {
  double length_3d = 0, length_uv = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a >= shape.cols() || b >= shape.cols()) continue;
      length_3d += (shape.col(a) - shape.col(b)).norm();
      length_uv += (mesh.uvs[mesh.triangle_uvs[t][k]] - mesh.uvs[mesh.triangle_uvs[t][(k + 1) % 3]]).norm();
    }
  }
  return length_uv > 0 ? 10.0 * length_3d / length_uv : 0;
}

MillimetreGrid millimetre_grid(const TriangleMesh& mesh, double mm_per_uv, double texel_mm) {
  if (!(mm_per_uv > 0)) throw Error("the mesh has no UV extent");
  if (!(texel_mm > 0)) throw Error("a texel must have a positive size");
  const int size = std::clamp(static_cast<int>(std::lround(mm_per_uv / texel_mm)), 32, 1024);
  return {rasterize_uv(mesh, size), size / mm_per_uv};
}

}  // namespace facecap
