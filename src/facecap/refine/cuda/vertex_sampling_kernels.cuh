#pragma once
// sample_vertices (vertex_samples.hpp) on the GPU: the occluding mesh's depth
// rasterised as the CPU rasteriser draws it (the same projection, culling,
// edge functions and perspective-correct depth, with multiply-adds left
// uncontracted so that the arithmetic is the CPU's), then each vertex's
// depth test (vertex_visibility) and bilinear colour (sample_bilinear_rgb8).
#include <cuda_runtime.h>

namespace facecap::cuda {

struct CameraView {
  float focal = 0, cx = 0, cy = 0;  // as PinholeCamera::project(Vec3f) uses them
  double focal_d = 0;               // for the depth test's z / f
};

struct ImageView {
  const unsigned char* bgr = nullptr;  // 8-bit BGR rows
  int width = 0, height = 0;
  int pitch = 0;  // bytes per row
};

// depth: width x height words, the bits of the nearest positive depth
// (0xffffffff where nothing was drawn).
void launch_depth_raster(const float* points, int num_points, const int* triangles, int num_triangles,
                         const CameraView& camera, float near_z, unsigned* depth, int width, int height,
                         cudaStream_t s);
// visible[i] and colour (3 floats, RGB in [0, 1], 0 where not visible) of each vertex.
void launch_vertex_samples(const float* points, const float* normals, int num_points, const CameraView& camera,
                           const unsigned* depth, const ImageView& image, float depth_tolerance, unsigned char* visible,
                           float* colour, cudaStream_t s);

}  // namespace facecap::cuda
