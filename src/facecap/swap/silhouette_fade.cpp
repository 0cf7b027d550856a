#include "facecap/swap/silhouette_fade.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "facecap/swap/weighted_channels.hpp"

namespace facecap {

namespace {

// Two passes of a box filter, `width` wide, whose variance (width^2 - 1) / 6
// is a Gaussian's of the given sigma: much cheaper than the Gaussian's taps.
void two_box_blur(const cv::Mat& in, cv::Mat& out, double sigma) {
  const int width = std::max(1, 2 * int(std::lround(0.5 * (std::sqrt(6 * sigma * sigma + 1) - 1))) + 1);
  cv::boxFilter(in, out, -1, cv::Size(width, width), cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
  cv::boxFilter(out, out, -1, cv::Size(width, width), cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
}

}  // namespace

void soften_turned_away(cv::Mat& render, const cv::Mat& turned, const cv::Mat& outline_px, const SilhouetteFade& fade) {
  // Where the render changes, and by how much: the surface turned away,
  // away from the outline (1 - near_outline), and the box around it.
  cv::Mat change(render.size(), CV_32F);
  int x0 = render.cols, y0 = render.rows, x1 = -1, y1 = -1;
  for (int y = 0; y < render.rows; ++y) {
    const float* t = turned.ptr<float>(y);
    const float* d = outline_px.ptr<float>(y);
    float* g = change.ptr<float>(y);
    for (int x = 0; x < render.cols; ++x) {
      g[x] = t[x] * (1.0f - fade.near_outline(d[x]));
      if (g[x] <= 0) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return;
  const cv::Rect box(cv::Point(x0, y0), cv::Point(x1 + 1, y1 + 1));
  // The colours around it, over three sigmas more.
  const double sigma = std::max(1.0, fade.band_px / 8.0);
  const int reach = int(std::ceil(3 * sigma));
  const cv::Rect roi = cv::Rect(box.x - reach, box.y - reach, box.width + 2 * reach, box.height + 2 * reach) &
                       cv::Rect(0, 0, render.cols, render.rows);
  const cv::Mat facing = 1.0f - turned(roi);
  cv::Mat weighted, weight;
  two_box_blur(times_weight(render(roi), facing), weighted, sigma);
  two_box_blur(facing, weight, sigma);
  for (int y = box.y; y < box.y + box.height; ++y) {
    auto* colour = render.ptr<cv::Vec3f>(y);
    const float* g = change.ptr<float>(y);
    const auto* around = weighted.ptr<cv::Vec3f>(y - roi.y) - roi.x;
    const float* w = weight.ptr<float>(y - roi.y) - roi.x;
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (g[x] <= 0 || w[x] < 1e-3f) continue;
      colour[x] = colour[x] * (1 - g[x]) + around[x] * (g[x] / w[x]);
    }
  }
}

}  // namespace facecap
