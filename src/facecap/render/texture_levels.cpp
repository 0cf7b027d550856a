#include "facecap/render/texture_levels.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace facecap {

TextureLevels::TextureLevels(const cv::Mat& texture, int min_size) {
  if (texture.empty()) return;
  levels_.push_back(texture);
  while (true) {
    const cv::Mat& last = levels_.back();
    const cv::Size half((last.cols + 1) / 2, (last.rows + 1) / 2);
    if (half.width < min_size || half.height < min_size) break;
    cv::Mat next;
    cv::resize(last, next, half, 0, 0, cv::INTER_AREA);
    levels_.push_back(next);
  }
}

float TextureLevels::lod_for(float texels_per_pixel) const {
  // Level k has a texel every 2^k texels of level 0 (mipmapping's choice).
  if (!(texels_per_pixel > 1.0f) || empty()) return 0.0f;
  return std::min(std::log2(texels_per_pixel), float(count() - 1));
}

float TextureLevels::to_level(int k, float c0, bool rows) const {
  if (k == 0) return c0;
  const float scale =
      rows ? float(levels_[k].rows) / float(levels_[0].rows) : float(levels_[k].cols) / float(levels_[0].cols);
  return (c0 + 0.5f) * scale - 0.5f;
}

float texels_per_pixel(const TriangleMesh& mesh, const Positions& points, const PinholeCamera& camera,
                       int texture_size) {
  std::vector<float> ratios;
  ratios.reserve(mesh.triangles.size());
  const float texels = float(texture_size);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Vec3f a = points.col(tri[0]), b = points.col(tri[1]), c = points.col(tri[2]);
    if (!(a.z() > 0 && b.z() > 0 && c.z() > 0) || (b - a).cross(c - a).dot(a) >= 0.0f) continue;
    const Vec2f pa = camera.project(a), pb = camera.project(b), pc = camera.project(c);
    const float image_area = 0.5f * std::abs((pb - pa).x() * (pc - pa).y() - (pb - pa).y() * (pc - pa).x());
    const Triangle& uv = mesh.triangle_uvs[t];
    const Vec2f ua = mesh.uvs[uv[0]] * texels, ub = mesh.uvs[uv[1]] * texels, uc = mesh.uvs[uv[2]] * texels;
    const float uv_area = 0.5f * std::abs((ub - ua).x() * (uc - ua).y() - (ub - ua).y() * (uc - ua).x());
    if (image_area > 1e-6f && uv_area > 0) ratios.push_back(std::sqrt(uv_area / image_area));
  }
  if (ratios.empty()) return 1.0f;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2];
}

}  // namespace facecap
