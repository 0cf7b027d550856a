#include "facecap/swap/residual_shading.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/render/uv_raster.hpp"

namespace facecap {

ResidualShading::ResidualShading(const TriangleMesh& mesh, const Positions& reference, ResidualShadingOptions options)
    : options_(options), vertex_uvs_(per_vertex_uvs(mesh)), mm_per_uv_(millimetres_per_uv(mesh, reference)) {
  if (!(mm_per_uv_ > 0)) throw Error("residual shading: the mesh has no UV extent");
  if (!(options_.low_pass_mm > 0)) throw Error("residual shading: the low-pass width must be positive");
  // About 3 texels per sigma: a grid this coarse is all the field needs.
  grid_ = std::clamp(static_cast<int>(std::lround(3.0 * mm_per_uv_ / options_.low_pass_mm)), 16, 256);
  sigma_texels_ = options_.low_pass_mm / mm_per_uv_ * (grid_ - 1);
}

cv::Mat ResidualShading::gains(std::span<const LitVertex> lit, const Positions& albedo) const {
  // Each lit vertex's ratio per channel, splatted bilinearly into the grid:
  // `sum` holds ratio x weight, `weight` the weight.
  cv::Mat sum(grid_, grid_, CV_32FC3, cv::Scalar::all(0)), weight(grid_, grid_, CV_32F, cv::Scalar(0));
  int samples = 0;
  for (const LitVertex& s : lit) {
    if (s.vertex >= albedo.cols() || s.vertex >= static_cast<int>(vertex_uvs_.size())) continue;
    cv::Vec3f ratio;  // BGR, as the albedo
    bool usable = true;
    for (int c = 0; c < 3; ++c) {
      const float predicted = s.shade * albedo(c, s.vertex);
      ratio[c] = s.observed[2 - c] / predicted;
      usable = usable && predicted > 0.02f && std::isfinite(ratio[c]);
    }
    if (!usable) continue;
    const Vec2f t = uv_to_texel(vertex_uvs_[s.vertex], grid_);
    const int x0 = std::clamp(static_cast<int>(std::floor(t.x())), 0, grid_ - 2);
    const int y0 = std::clamp(static_cast<int>(std::floor(t.y())), 0, grid_ - 2);
    const float fx = std::clamp(t.x() - float(x0), 0.0f, 1.0f), fy = std::clamp(t.y() - float(y0), 0.0f, 1.0f);
    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    for (int k = 0; k < 4; ++k) {
      const int x = x0 + (k & 1), y = y0 + (k >> 1);
      sum.at<cv::Vec3f>(y, x) += w[k] * ratio;
      weight.at<float>(y, x) += w[k];
    }
    ++samples;
  }
  cv::Mat field(grid_, grid_, CV_32FC3, cv::Scalar::all(1));
  if (samples < 50) return field;
  // Normalised convolution; far from any sample the field fades to 1
  // (`prior`: the weight of one half-seen texel) rather than stretching the
  // nearest ratio over the unseen side of a turned head.
  cv::GaussianBlur(sum, sum, cv::Size(0, 0), sigma_texels_, sigma_texels_, cv::BORDER_CONSTANT);
  cv::GaussianBlur(weight, weight, cv::Size(0, 0), sigma_texels_, sigma_texels_, cv::BORDER_CONSTANT);
  double max_weight = 0;
  cv::minMaxLoc(weight, nullptr, &max_weight);
  const float prior = 0.05f * static_cast<float>(max_weight);
  const double total_weight = std::max(1e-9, cv::sum(weight)[0]);
  std::vector<cv::Mat> channels;
  cv::split(sum, channels);
  for (cv::Mat& f : channels) {
    f = (f + prior) / (weight + prior);
    // Mean 1 where the samples are: the overall level and colour are the
    // SH lighting's and light_colour()'s.
    const double mean = cv::sum(f.mul(weight))[0] / total_weight;
    if (mean > 0) f /= mean;
    cv::min(cv::max(f, 1.0 / options_.max_gain), options_.max_gain, f);
  }
  cv::merge(channels, field);
  return field;
}

}  // namespace facecap
