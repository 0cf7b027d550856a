#include "facecap/swap/light_colour.hpp"

#include <algorithm>

namespace facecap {

Vec3f light_colour(std::span<const LitVertex> lit, const Positions& albedo, const LightColourOptions& options) {
  // Per channel: sum of the observed colour over sum of albedo x shading,
  // over the vertices seen squarely now and in the appearance frames.
  Eigen::Vector3d observed = Eigen::Vector3d::Zero(), predicted = Eigen::Vector3d::Zero();
  size_t samples = 0;
  for (const LitVertex& s : lit) {
    if (s.vertex >= albedo.cols()) continue;
    for (int c = 0; c < 3; ++c) {
      observed[c] += s.observed[2 - c];
      predicted[c] += albedo(c, s.vertex) * s.shade;
    }
    ++samples;
  }
  if (samples < 50 || (predicted.array() <= 0).any() || (observed.array() <= 0).any()) return Vec3f::Ones();
  const Eigen::Vector3d ratio = observed.cwiseQuotient(predicted);
  Vec3f gain = (ratio / ratio.mean()).cast<float>();
  for (int c = 0; c < 3; ++c) gain[c] = std::clamp(gain[c], 1.0f / options.max_gain, options.max_gain);
  return gain;
}

}  // namespace facecap
