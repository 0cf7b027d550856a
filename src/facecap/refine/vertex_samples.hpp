#pragma once
// What the shading estimators read from a frame at a mesh level: each
// vertex's colour (bilinear, at its projection) and whether it is visible
// (depth test against the rasterised level, normal facing the camera).
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

struct VertexSamples {
  Positions colour;           // 3 x N, RGB in [0, 1]
  std::vector<bool> visible;  // inside the image, passes the depth test, faces the camera
  int visible_count = 0;
};

// `image`: BGR 8-bit at the resolution `camera` describes. Only vertices in
// `active` (all when empty) are rasterised and sampled.
VertexSamples sample_vertices(const cv::Mat& image, const Positions& camera_points, const Positions& camera_normals,
                              const std::vector<Triangle>& triangles, const PinholeCamera& camera);
// The same with caller-owned raster buffers, reused across frames (a 720p
// buffer is 15 MB: allocating it per frame costs more than rasterising).
VertexSamples sample_vertices(const cv::Mat& image, const Positions& camera_points, const Positions& camera_normals,
                              const std::vector<Triangle>& triangles, const PinholeCamera& camera,
                              RasterBuffers& buffers);
// The same with the depth test against another mesh of the same surface:
// a finer hierarchy level's base surface is the coarse one, whose fewer
// triangles draw the same depth sooner (refine_bench at 720p: 70k triangles
// 4.7-5.5 ms, the coarse 18k 2.6-3.7 ms).
VertexSamples sample_vertices(const cv::Mat& image, const Positions& camera_points, const Positions& camera_normals,
                              const Positions& occluder_points, const std::vector<Triangle>& occluder_triangles,
                              const PinholeCamera& camera, RasterBuffers& buffers);

// Drops the observations within `rings` rings of a vertex that is not
// observed (the silhouette, the edge of the skin mask) or of a hole in the
// mesh: vertices on `open_boundary` (the rims of the eye and mouth holes; none
// when empty) are one ring from what shows through the hole. There a vertex's
// bilinear sample mixes in the background, the eyeball or the teeth, and its
// normal depends on neighbours no pixel constrains: the displacement solve
// bends the surface to explain them, and the lighting and albedo take an eye
// white for bright skin.
void erode_observations(VertexSamples& samples, const VertexAdjacency& adjacency, int rings,
                        const std::vector<bool>& open_boundary = {});

// `mask` grown by `rings` rings of neighbours (the rings must be symmetric, as
// a mesh's one-rings are).
std::vector<bool> grow_by_rings(const std::vector<bool>& mask, const VertexAdjacency& adjacency, int rings);

// Drops the observations of vertices seen more obliquely than `min_facing`
// (the cosine between the normal and the ray to the camera). There a
// displacement along the normal moves the vertex's image point by a sizeable
// part of itself while its colour is sampled where the base vertex projects,
// and the bilinear sample spans a stretch of skin foreshortened by cos.
void drop_oblique_observations(VertexSamples& samples, const Positions& camera_points, const Positions& camera_normals,
                               float min_facing);

// An 8-bit image pyramid: level 0 the frame, each next level half the size.
// The refinement reads level k - 1 - l for mesh level l of k.
std::vector<cv::Mat> image_pyramid(const cv::Mat& bgr8, int levels);

}  // namespace facecap
