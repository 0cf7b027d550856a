#pragma once
// Image-space comparisons of a rendered face with a frame: the photometric
// error of paper Fig. 4.11 (mean absolute difference, 0-255, over the face
// pixels, and a heat map), and per-pixel interpolated attributes (normals,
// depth) for comparing surfaces.
#include <opencv2/core.hpp>

#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

// Interpolates a per-vertex attribute (3 x N) over the covered pixels into a
// CV_32FC3 image (x, y, z in channels 0, 1, 2); uncovered pixels are 0.
cv::Mat interpolate_attribute(const RasterBuffers& buffers, const std::vector<Triangle>& triangles,
                              const Positions& attribute);

// The geometric normal of the triangle under each covered pixel (unit,
// camera frame) in a CV_32FC3 image: a triangle mesh's true surface normal,
// unlike interpolated vertex normals, which depend on the mesh resolution.
cv::Mat face_normal_image(const RasterBuffers& buffers, const std::vector<Triangle>& triangles,
                          const Positions& camera_points);

struct PhotometricError {
  double mean_abs = 0;  // 0-255, averaged over channels and covered pixels
  int pixels = 0;
  cv::Mat heat_map;  // BGR 8-bit, the frame dimmed with the error coloured over the face (when requested)
};

// Renders albedo * l^T SH(n) for the mesh and compares it with `frame`
// (BGR 8-bit) over the pixels the mesh covers.
PhotometricError photometric_error(const cv::Mat& frame, const Positions& camera_points,
                                   const std::vector<Triangle>& triangles, const Positions& camera_normals,
                                   const Positions& albedo, const ShCoeffs& lighting, const PinholeCamera& camera,
                                   bool heat_map = false);

}  // namespace facecap
