#include "facecap/swap/light_colour.hpp"

#include <algorithm>

#include "facecap/core/image_sampling.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

Vec3f light_colour(const cv::Mat& frame, const Positions& camera_points, const Positions& camera_normals,
                   const Positions& albedo, const std::vector<float>& seen, const PinholeCamera& camera,
                   const ShCoeffs& lighting, const LightColourOptions& options) {
  // Per channel: sum of the observed colour over sum of albedo x shading,
  // over the vertices seen squarely now and in the appearance frames.
  Eigen::Vector3d observed = Eigen::Vector3d::Zero(), predicted = Eigen::Vector3d::Zero();
  int samples = 0;
  const Eigen::Index n = std::min<Eigen::Index>(
      {camera_points.cols(), camera_normals.cols(), albedo.cols(), static_cast<Eigen::Index>(seen.size())});
  for (Eigen::Index v = 0; v < n; ++v) {
    if (!(seen[v] > options.min_seen)) continue;
    const Vec3f p = camera_points.col(v);
    const Vec3f normal = camera_normals.col(v);
    if (!(p.z() > 0) || !(view_facing(p, normal) >= options.min_facing)) continue;
    const Vec2f q = camera.project(p);
    if (!(q.x() >= 0 && q.y() >= 0 && q.x() <= frame.cols - 1 && q.y() <= frame.rows - 1)) continue;
    const Vec3f n_viewer = to_viewer_frame(normal);
    const float shade = sh_shade(lighting, n_viewer.x(), n_viewer.y(), n_viewer.z());
    if (!(shade > 0.05f)) continue;
    const Vec3f rgb = sample_bilinear_rgb8(frame, q.x(), q.y());  // RGB in [0, 1]
    for (int c = 0; c < 3; ++c) {
      observed[c] += rgb[2 - c];
      predicted[c] += albedo(c, v) * shade;
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
