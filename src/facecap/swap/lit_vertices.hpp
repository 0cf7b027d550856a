#pragma once
// The target face's vertices a frame shows squarely under light, with the
// colour the frame has there: the samples light_colour() and
// ResidualShading compare with the target's own albedo.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/spherical_harmonics.hpp"

namespace facecap {

struct LitVertex {
  int vertex = 0;
  Vec3f observed;   // RGB in [0, 1], sampled at the vertex's projection
  float shade = 0;  // SH irradiance on the vertex's normal (eq. 4.9)
};

// Vertices with `seen` above `min_seen`, in front of the camera, within
// acos(min_facing) of the view ray, inside `frame` (BGR 8-bit) and lit
// (shade above 0.05); the first `count` vertices are considered.
std::vector<LitVertex> lit_vertices(const cv::Mat& frame, const Positions& camera_points,
                                    const Positions& camera_normals, const std::vector<float>& seen, int count,
                                    const PinholeCamera& camera, const ShCoeffs& lighting, float min_seen,
                                    float min_facing);

}  // namespace facecap
