#pragma once
// The colour of the target's light, frame by frame. The SH lighting of
// eq. 4.9 is one grey irradiance shared by the three channels, so a light
// that turns warmer, or a camera whose white balance drifts, changes the
// target face's colour but not its lighting, and a new face rendered under
// that lighting alone keeps the colour of the first frames. Here the
// target's face, against its own albedo (the appearance frames' mean)
// shaded by this frame's lighting, gives one ratio per channel; their
// chromatic part (mean 1: brightness is the SH lighting's business) tints
// the new face alike.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/spherical_harmonics.hpp"

namespace facecap {

struct LightColourOptions {
  float min_facing = 0.5f;  // vertices whose normal is within 60 degrees of the view ray
  float min_seen = 0.05f;   // albedo weight a vertex needs (the appearance frames saw it)
  float max_gain = 1.25f;   // per-channel gains are clamped to [1 / max_gain, max_gain]
};

// `frame`: BGR 8-bit; `camera_points`, `camera_normals`: the target face's
// vertices and unit normals in camera space; `albedo`: 3 x N BGR in [0, 1]
// with `seen` its per-vertex weight. Returns the BGR gains (mean 1), or
// (1, 1, 1) where too few vertices are seen.
Vec3f light_colour(const cv::Mat& frame, const Positions& camera_points, const Positions& camera_normals,
                   const Positions& albedo, const std::vector<float>& seen, const PinholeCamera& camera,
                   const ShCoeffs& lighting, const LightColourOptions& options = {});

}  // namespace facecap
