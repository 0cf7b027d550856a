#include "facecap/compose/laplacian_blend.hpp"

#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// sum += (d - up) * m, per pixel (d, up, sum: CV_32FC3, m: CV_32F): a
// level's band, masked, added to the sum of the coarser levels' (pyrUp'd to
// this level's size).
void add_masked_band(const cv::Mat& d, const cv::Mat& up, const cv::Mat& m, cv::Mat& sum) {
  for (int y = 0; y < d.rows; ++y) {
    const float* dp = d.ptr<float>(y);
    const float* upp = up.ptr<float>(y);
    const float* mp = m.ptr<float>(y);
    float* sp = sum.ptr<float>(y);
    for (int x = 0; x < d.cols; ++x) {
      for (int c = 0; c < 3; ++c) sp[3 * x + c] += (dp[3 * x + c] - upp[3 * x + c]) * mp[x];
    }
  }
}

}  // namespace

cv::Mat laplacian_blend(const cv::Mat& base, const cv::Mat& layer, const cv::Mat& mask, int levels) {
  // Laplacian pyramids are linear, so blending the layer's and the base's
  // bands with the mask's Gaussian pyramid equals adding to the base the
  // blended bands of their difference: one pyramid instead of two.
  if (base.type() != CV_8UC3 || layer.type() != CV_8UC3 || mask.type() != CV_8U || base.size() != layer.size() ||
      base.size() != mask.size())
    throw Error("laplacian blend: needs a BGR 8-bit base and layer and an 8-bit mask, all of one size");
  cv::Mat d(base.size(), CV_32FC3), m;
  for (int y = 0; y < base.rows; ++y) {
    const uchar* b = base.ptr<uchar>(y);
    const uchar* l = layer.ptr<uchar>(y);
    float* dp = d.ptr<float>(y);
    for (int x = 0; x < 3 * base.cols; ++x) dp[x] = float(l[x]) - float(b[x]);
  }
  mask.convertTo(m, CV_32F, 1.0 / 255.0);
  std::vector<cv::Mat> gd{d}, gm{m};
  for (int l = 1; l < levels; ++l) {
    if (gd.back().cols < 8 || gd.back().rows < 8) break;
    cv::Mat x, z;
    cv::pyrDown(gd.back(), x);
    cv::pyrDown(gm.back(), z);
    gd.push_back(std::move(x));
    gm.push_back(std::move(z));
  }
  const int n = static_cast<int>(gd.size());
  // The coarsest Gaussian level, masked; then each finer band, masked, added
  // on the way up, down to level 1. (This file is compiled without
  // floating-point contraction: the fused passes below make the same sums
  // in the same order as the pass each they replaced.)
  const cv::Mat nothing_coarser = cv::Mat::zeros(gd[n - 1].size(), CV_32FC3);
  cv::Mat result = nothing_coarser.clone();
  add_masked_band(gd[n - 1], nothing_coarser, gm[n - 1], result);
  cv::Mat detail_up, coarse_up;
  for (int l = n - 2; l >= 1; --l) {
    cv::pyrUp(gd[l + 1], detail_up, gd[l].size());
    cv::pyrUp(result, coarse_up, gd[l].size());
    add_masked_band(gd[l], detail_up, gm[l], coarse_up);
    std::swap(result, coarse_up);
  }
  // Level 0 (the window's size, where the passes over memory cost most) in
  // one pass: its band, the coarser levels' sum and the base, rounded and
  // saturated as convertTo would.
  if (n > 1) {
    cv::pyrUp(gd[1], detail_up, gd[0].size());
    cv::pyrUp(result, coarse_up, gd[0].size());
  }
  cv::Mat out(base.size(), CV_8UC3);
  for (int y = 0; y < base.rows; ++y) {
    const uchar* b = base.ptr<uchar>(y);
    uchar* o = out.ptr<uchar>(y);
    if (n == 1) {
      const float* r = result.ptr<float>(y);
      for (int x = 0; x < 3 * base.cols; ++x) o[x] = cv::saturate_cast<uchar>(r[x] + float(b[x]));
      continue;
    }
    const float* dp = gd[0].ptr<float>(y);
    const float* du = detail_up.ptr<float>(y);
    const float* cu = coarse_up.ptr<float>(y);
    const float* mp = gm[0].ptr<float>(y);
    for (int x = 0; x < base.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int i = 3 * x + c;
        const float level0 = cu[i] + (dp[i] - du[i]) * mp[x];
        o[i] = cv::saturate_cast<uchar>(level0 + float(b[i]));
      }
    }
  }
  return out;
}

cv::Mat feather_mask(const cv::Mat& mask, int inset, double feather) {
  cv::Mat m = mask.clone();
  if (inset > 0) cv::erode(m, m, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * inset + 1, 2 * inset + 1)));
  if (feather > 0) cv::GaussianBlur(m, m, cv::Size(0, 0), feather);
  return m;
}

}  // namespace facecap
