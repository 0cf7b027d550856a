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

struct LitVertexOptions {
  float min_facing = 0.5f;  // vertices whose normal is within 60 degrees of the view ray
  float min_seen = 0.05f;   // albedo weight a vertex needs (the appearance frames saw it)
};

// Vertices with `seen` above min_seen, in front of the camera, within
// acos(min_facing) of the view ray, inside `frame` (BGR 8-bit) and lit
// (shade above 0.05). `camera_points`, `camera_normals`: the face's vertices
// and unit normals in camera space.
std::vector<LitVertex> lit_vertices(const cv::Mat& frame, const Positions& camera_points,
                                    const Positions& camera_normals, const std::vector<float>& seen,
                                    const PinholeCamera& camera, const ShCoeffs& lighting,
                                    const LitVertexOptions& options = {});

}  // namespace facecap
