#include "facecap/swap/lit_vertices.hpp"

#include <algorithm>

#include "facecap/core/image_sampling.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

std::vector<LitVertex> lit_vertices(const cv::Mat& frame, const Positions& camera_points,
                                    const Positions& camera_normals, const std::vector<float>& seen,
                                    const PinholeCamera& camera, const ShCoeffs& lighting,
                                    const LitVertexOptions& options) {
  const Eigen::Index n =
      std::min<Eigen::Index>({camera_points.cols(), camera_normals.cols(), static_cast<Eigen::Index>(seen.size())});
  std::vector<LitVertex> lit;
  lit.reserve(static_cast<size_t>(std::max<Eigen::Index>(0, n)));
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
    lit.push_back({static_cast<int>(v), sample_bilinear_rgb8(frame, q.x(), q.y()), shade});
  }
  return lit;
}

}  // namespace facecap
