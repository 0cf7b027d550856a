#pragma once
// One weight per texel applied to every channel of an image: the weighted
// sums and normalised (weighted-mean) blurs the face textures are built
// from, texel by texel, with no copy of the weight per channel.
#include <opencv2/core.hpp>

namespace facecap {

// `value` (CV_32FC(n)) times `weight` (CV_32F, the same size).
cv::Mat times_weight(const cv::Mat& value, const cv::Mat& weight);

// `value` (CV_32FC(n)) divided by max(`weight`, `least`) (CV_32F), in place.
void divide_by_weight(cv::Mat& value, const cv::Mat& weight, float least);

}  // namespace facecap
