#include "facecap/detect/shot_cut.hpp"

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {
const cv::Size kThumbnail(64, 36);
}  // namespace

bool ShotCutDetector::next(const cv::Mat& grey) {
  last_correlation_ = 1.0;
  if (grey.empty()) return false;
  cv::Mat thumb;
  cv::resize(grey, thumb, kThumbnail, 0, 0, cv::INTER_AREA);
  thumb.convertTo(thumb, CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(thumb, mean, stddev);
  if (stddev[0] < options_.min_contrast) return false;
  // Zero mean, unit norm: the dot product of two is their correlation.
  thumb -= mean[0];
  thumb /= cv::norm(thumb);
  const bool cut = !reference_.empty() && (last_correlation_ = reference_.dot(thumb)) < options_.min_correlation;
  reference_ = thumb;
  return cut;
}

}  // namespace facecap
