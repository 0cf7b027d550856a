#pragma once
// Bilinear image lookups at sub-pixel positions (pixel centres at integers).
#include <algorithm>
#include <opencv2/core.hpp>

#include "facecap/core/geometry.hpp"
#include "facecap/core/uv_texel.hpp"

namespace facecap {

// Samples a float image of N channels (CV_32FC(N)); positions outside are
// clamped to the border.
template <int N>
inline cv::Vec<float, N> sample_bilinear_channels(const cv::Mat& image, float x, float y) {
  x = std::clamp(x, 0.0f, float(image.cols - 1));
  y = std::clamp(y, 0.0f, float(image.rows - 1));
  const int x0 = std::min(int(x), std::max(0, image.cols - 2));
  const int y0 = std::min(int(y), std::max(0, image.rows - 2));
  const int x1 = std::min(x0 + 1, image.cols - 1);
  const int y1 = std::min(y0 + 1, image.rows - 1);
  const float fx = x - x0, fy = y - y0;
  using Pixel = cv::Vec<float, N>;
  const Pixel* r0 = image.ptr<Pixel>(y0);
  const Pixel* r1 = image.ptr<Pixel>(y1);
  return (r0[x0] * (1 - fx) + r0[x1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x1] * fx) * fy;
}

// Samples a CV_32FC3 image; positions outside are clamped to the border.
inline Vec3f sample_bilinear(const cv::Mat& image, float x, float y) {
  const cv::Vec3f v = sample_bilinear_channels<3>(image, x, y);
  return {v[0], v[1], v[2]};
}

// Samples an 8-bit BGR image; returns RGB in [0, 1]. Positions outside are
// clamped to the border.
inline Vec3f sample_bilinear_rgb8(const cv::Mat& bgr8, float x, float y) {
  x = std::clamp(x, 0.0f, float(bgr8.cols - 1));
  y = std::clamp(y, 0.0f, float(bgr8.rows - 1));
  const int x0 = std::min(int(x), std::max(0, bgr8.cols - 2));
  const int y0 = std::min(int(y), std::max(0, bgr8.rows - 2));
  const int x1 = std::min(x0 + 1, bgr8.cols - 1), y1 = std::min(y0 + 1, bgr8.rows - 1);
  const float fx = x - x0, fy = y - y0;
  const auto& a = bgr8.at<cv::Vec3b>(y0, x0);
  const auto& b = bgr8.at<cv::Vec3b>(y0, x1);
  const auto& c = bgr8.at<cv::Vec3b>(y1, x0);
  const auto& d = bgr8.at<cv::Vec3b>(y1, x1);
  Vec3f out;
  for (int k = 0; k < 3; ++k) {
    const float v = (a[k] * (1 - fx) + b[k] * fx) * (1 - fy) + (c[k] * (1 - fx) + d[k] * fx) * fy;
    out[2 - k] = v / 255.0f;
  }
  return out;
}

// Samples a texture at UV (u right, v up, OBJ convention) into RGB, for a
// square BGR CV_32FC3 texture (texel centres as core/uv_texel.hpp says).
inline Vec3f sample_uv_rgb(const cv::Mat& texture_bgr, const Vec2f& uv) {
  const Vec2f texel = uv_to_texel(uv, texture_bgr.cols);
  const Vec3f bgr = sample_bilinear(texture_bgr, texel.x(), texel.y());
  return {bgr.z(), bgr.y(), bgr.x()};
}

}  // namespace facecap
