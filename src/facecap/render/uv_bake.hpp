#pragma once
// Bakes a per-vertex attribute into a texture in UV space (the mesh's
// per-corner UVs), e.g. the recovered albedo as `albedo.png` for the ICT UV
// layout, ready for Blender or three.js, or the refinement's displacements as
// a detail map a frame (pipeline/detail_maps.hpp).
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/core/mesh.hpp"
#include "facecap/render/uv_raster.hpp"

namespace facecap {

// Bakes of one mesh's triangles into one texel map (rasterize_uv), as often
// as asked: which texels the triangles cover, and which texels grow the
// islands, are found once.
class UvBaker {
 public:
  // triangles: those `map` was rasterised from. grow_texels: how far the
  // islands grow, so that texture filtering does not pull in the texels no
  // triangle covers. Keeps only what the bakes read (the covered texels'
  // corners and weights, the border's sources), not the map.
  UvBaker(const std::vector<Triangle>& triangles, const UvTexelMap& map, int grow_texels = 2);

  // values: C x N per-vertex values (1 <= C <= 4). Returns a CV_32FC(C)
  // image of size() square, channels in the rows' order: each covered
  // texel the barycentric interpolation of its triangle's corner values; each
  // texel of the grown border the largest of its neighbours nearer the island
  // (per channel: a dilation by a 3 x 3 square a ring); 0 elsewhere.
  // Throws facecap::Error for another number of rows.
  cv::Mat bake(const Eigen::MatrixXf& values) const;

  int size() const { return size_; }

 private:
  int size_;  // the texture is size_ x size_
  // The covered texels: each one's index, its triangle's corners and its
  // barycentric weights, in texel order.
  std::vector<int> covered_;
  std::vector<Triangle> corners_;
  std::vector<Vec3f> weights_;
  // Each ring of the grown border: its texels and, in compressed rows, the
  // neighbours each takes its value from (covered, or in an earlier ring).
  struct Ring {
    std::vector<int> texels, offsets, sources;
  };
  std::vector<Ring> rings_;
};

// values: 3 x N RGB in [0, 1]. Returns a BGR 8-bit image of size x size;
// texels no triangle covers stay black; a 2-texel dilation hides seams.
cv::Mat bake_uv_texture(const TriangleMesh& mesh, const Positions& values, int size = 1024);

}  // namespace facecap
