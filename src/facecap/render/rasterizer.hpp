#pragma once
// Software rasteriser for triangle meshes under the pinhole camera of eq. 4.2.
// Produces depth, triangle-id and perspective-correct barycentric buffers;
// shading and visibility are computed from those buffers.
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"

namespace facecap {

struct RasterBuffers {
  int width = 0;
  int height = 0;
  std::vector<float> depth;   // camera-space z; +inf where nothing was drawn
  std::vector<int> triangle;  // index into the triangle list; -1 for background
  std::vector<Vec2f> bary;    // perspective-correct weights of corners 1 and 2 (corner 0 = 1 - sum)
  // The box [x0, x1) x [y0, y1) holding every pixel the last rasterize()
  // drew; outside it depth and triangle hold the background, so the next
  // call clears only this box (a face covers a fraction of a 720p frame).
  int drawn_x0 = 0, drawn_x1 = 0, drawn_y0 = 0, drawn_y1 = 0;

  // Every pixel the background (and nothing drawn).
  void resize(int w, int h);
  bool covered(int x, int y) const { return triangle[size_t(y) * width + x] >= 0; }
};

struct RasterOptions {
  bool cull_back_faces = true;  // skip triangles whose normal faces away from the camera
  float near_z = 1.0f;          // cm; triangles with a vertex closer than this are skipped
};

// Rasterises camera-space vertices (3 x N, cm). Pixel (x, y) samples the
// image point (x, y): pixel centres lie at integer coordinates, as landmarks do.
void rasterize(const Positions& camera_points, const std::vector<Triangle>& triangles, const PinholeCamera& camera,
               RasterBuffers& out, const RasterOptions& options = {});

// Per-vertex visibility: the vertex projects inside the image, passes the
// depth test against the buffers (within `depth_tolerance` cm, plus the depth
// the surface's slope spans over the vertex's distance to its pixel centre),
// and its normal (camera space) faces the camera.
std::vector<bool> vertex_visibility(const Positions& camera_points, const Positions& camera_normals,
                                    const PinholeCamera& camera, const RasterBuffers& buffers,
                                    float depth_tolerance = 0.15f);

}  // namespace facecap
