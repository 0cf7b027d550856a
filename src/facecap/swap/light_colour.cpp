#include "facecap/swap/light_colour.hpp"

#include <algorithm>

#include "facecap/swap/lit_vertices.hpp"

namespace facecap {

Vec3f light_colour(const cv::Mat& frame, const Positions& camera_points, const Positions& camera_normals,
                   const Positions& albedo, const std::vector<float>& seen, const PinholeCamera& camera,
                   const ShCoeffs& lighting, const LightColourOptions& options) {
  // Per channel: sum of the observed colour over sum of albedo x shading,
  // over the vertices seen squarely now and in the appearance frames.
  Eigen::Vector3d observed = Eigen::Vector3d::Zero(), predicted = Eigen::Vector3d::Zero();
  const std::vector<LitVertex> lit =
      lit_vertices(frame, camera_points, camera_normals, seen, static_cast<int>(albedo.cols()), camera, lighting,
                   options.min_seen, options.min_facing);
  for (const LitVertex& s : lit) {
    for (int c = 0; c < 3; ++c) {
      observed[c] += s.observed[2 - c];
      predicted[c] += albedo(c, s.vertex) * s.shade;
    }
  }
  const size_t samples = lit.size();
  if (samples < 50 || (predicted.array() <= 0).any() || (observed.array() <= 0).any()) return Vec3f::Ones();
  const Eigen::Vector3d ratio = observed.cwiseQuotient(predicted);
  Vec3f gain = (ratio / ratio.mean()).cast<float>();
  for (int c = 0; c < 3; ++c) gain[c] = std::clamp(gain[c], 1.0f / options.max_gain, options.max_gain);
  return gain;
}

}  // namespace facecap
