#pragma once
// Lighting estimation, §4.3.1, eq. 4.9: nine SH coefficients l shared by the
// colour channels from the visible vertices of the coarsest level,
//   E(l) = sum_i sum_c (rho_ic l^T SH(n_i) - I_ic)^2 + w1 ||l - l_prev||^2,
// w1 = 0.005, as the 9 x 9 normal equations of the stacked system.
#include <optional>

#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/refine/vertex_samples.hpp"

namespace facecap {

struct LightingOptions {
  double temporal_weight = 0.005;  // w1 of eq. 4.9 (intensities in [0, 1])
  // Ridge on the second-band coefficients l4..l8, relative to the data's
  // weight (sum of rho^2 over the rows). Seen from the front, the visible
  // normals cluster around the view direction, where 1, n_z and 3 n_z^2 - 1
  // are nearly collinear: many coefficient vectors shade the face alike. A
  // Lambertian surface attenuates band 2 of the irradiance (kernel pi,
  // 2 pi / 3, pi / 4), so real irradiance has little energy there; this
  // picks that member of the ambiguous set.
  double band2_ridge = 0.03;
  // Iteratively reweighted rounds with Huber weights (scale 1.5 x the median
  // absolute residual), for footage with highlights or occlusions. Off by
  // default: on the synthetic truth it raised the lighting error (0.15 -> 0.26).
  int robust_iterations = 0;
};

// normals: camera frame (converted to the viewer frame for SH); albedo RGB.
ShCoeffs estimate_lighting(const VertexSamples& samples, const Positions& camera_normals, const Positions& albedo,
                           const std::optional<ShCoeffs>& previous, const LightingOptions& options = {});

}  // namespace facecap
