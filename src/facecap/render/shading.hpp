#pragma once
// Lambertian shading of rasterised meshes with the SH lighting of eq. 4.7,
// and per-vertex attribute interpolation over the raster buffers.
#include <opencv2/core.hpp>

#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

// Normals enter the SH basis in the viewer frame (x right, y up, z toward
// the viewer), so that l[2] > 0 lights from above and l[3] > 0 from the
// camera, as in the paper. Camera-frame vectors (y down, z forward) convert:
inline Vec3f to_viewer_frame(const Vec3f& n_camera) { return {n_camera.x(), -n_camera.y(), -n_camera.z()}; }

// Draws albedo * l^T SH(n) with per-pixel interpolated albedo (3 x N, RGB in
// [0, 1]) and normals (3 x N, camera frame) over `canvas` (BGR, CV_32FC3),
// where the buffers are covered
// (RGB albedo, BGR canvas).
void shade_lambertian(const RasterBuffers& buffers, const std::vector<Triangle>& triangles, const Positions& albedo,
                      const Positions& camera_normals, const ShCoeffs& lighting, cv::Mat& canvas);

// Writes per-vertex colours (3 x N, RGB in [0, 1]) interpolated over the
// covered pixels into `canvas` (BGR, CV_32FC3), without lighting.
void shade_vertex_colors(const RasterBuffers& buffers, const std::vector<Triangle>& triangles, const Positions& colors,
                         cv::Mat& canvas);

// Interpolates a per-vertex attribute at a covered pixel.
inline Vec3f interpolate(const RasterBuffers& b, const std::vector<Triangle>& triangles, const Positions& attribute,
                         size_t pixel) {
  const Triangle& t = triangles[b.triangle[pixel]];
  const Vec2f w = b.bary[pixel];
  return (1.0f - w.x() - w.y()) * attribute.col(t[0]) + w.x() * attribute.col(t[1]) + w.y() * attribute.col(t[2]);
}

}  // namespace facecap
