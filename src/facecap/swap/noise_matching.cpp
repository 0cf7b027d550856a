#include "facecap/swap/noise_matching.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "facecap/swap/wide_blur.hpp"

namespace facecap {

namespace {

// Cumulative histogram of one channel over the mask, normalised to [0, 1].
std::vector<double> cdf(const cv::Mat& channel, const cv::Mat& mask, float lo, float hi, int bins) {
  std::vector<double> h(bins, 0.0);
  double total = 0;
  for (int y = 0; y < channel.rows; ++y) {
    const float* c = channel.ptr<float>(y);
    const uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < channel.cols; ++x) {
      if (!m[x]) continue;
      const int b = std::clamp(static_cast<int>((c[x] - lo) / (hi - lo) * bins), 0, bins - 1);
      h[b] += 1;
      total += 1;
    }
  }
  double run = 0;
  for (double& v : h) {
    run += v;
    v = total > 0 ? run / total : 0;
  }
  return h;
}

}  // namespace

cv::Mat match_histograms(const cv::Mat& source, const cv::Mat& source_mask, const cv::Mat& target,
                         const cv::Mat& target_mask, float lo, float hi, int bins) {
  std::vector<cv::Mat> s, t;
  cv::split(source, s);
  cv::split(target, t);
  const float width = (hi - lo) / bins;
  for (size_t c = 0; c < s.size(); ++c) {
    const std::vector<double> cs = cdf(s[c], source_mask, lo, hi, bins);
    const std::vector<double> ct = cdf(t[c], target_mask, lo, hi, bins);
    // Transfer function: each source bin to the target bin of equal cumulative share.
    std::vector<float> to(bins);
    for (int b = 0; b < bins; ++b) {
      const int k = static_cast<int>(std::lower_bound(ct.begin(), ct.end(), cs[b] - 1e-12) - ct.begin());
      to[b] = lo + (std::min(k, bins - 1) + 0.5f) * width;
    }
    for (int y = 0; y < s[c].rows; ++y) {
      float* p = s[c].ptr<float>(y);
      for (int x = 0; x < s[c].cols; ++x) {
        const int b = std::clamp(static_cast<int>((p[x] - lo) / (hi - lo) * bins), 0, bins - 1);
        p[x] = to[b];
      }
    }
  }
  cv::Mat out;
  cv::merge(s, out);
  return out;
}

cv::Mat fine_residual(const cv::Mat& albedo, double sigma) { return albedo - wide_blur(albedo, sigma); }

}  // namespace facecap
