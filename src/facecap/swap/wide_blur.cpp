#include "facecap/swap/wide_blur.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace facecap {

cv::Mat wide_blur(const cv::Mat& image, double sigma, int border) {
  const int factor = std::max(1, static_cast<int>(sigma / 4.0));
  cv::Mat out;
  if (factor == 1) {
    cv::GaussianBlur(image, out, cv::Size(0, 0), sigma, sigma, border);
    return out;
  }
  const cv::Size small((image.cols + factor - 1) / factor, (image.rows + factor - 1) / factor);
  cv::resize(image, out, small, 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(out, out, cv::Size(0, 0), sigma / factor, sigma / factor, border);
  cv::resize(out, out, image.size(), 0, 0, cv::INTER_LINEAR);
  return out;
}

}  // namespace facecap
