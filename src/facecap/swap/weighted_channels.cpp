#include "facecap/swap/weighted_channels.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

void check(const cv::Mat& value, const cv::Mat& weight) {
  if (value.depth() != CV_32F || weight.type() != CV_32F || value.size() != weight.size())
    throw Error("weighted channels: a float image and a float weight of its size are needed");
}

}  // namespace

cv::Mat times_weight(const cv::Mat& value, const cv::Mat& weight) {
  check(value, weight);
  const int channels = value.channels();
  cv::Mat out(value.size(), value.type());
  for (int y = 0; y < value.rows; ++y) {
    const float* v = value.ptr<float>(y);
    const float* w = weight.ptr<float>(y);
    float* o = out.ptr<float>(y);
    for (int x = 0; x < value.cols; ++x)
      for (int c = 0; c < channels; ++c) o[x * channels + c] = v[x * channels + c] * w[x];
  }
  return out;
}

void divide_by_weight(cv::Mat& value, const cv::Mat& weight, float least) {
  check(value, weight);
  const int channels = value.channels();
  for (int y = 0; y < value.rows; ++y) {
    float* v = value.ptr<float>(y);
    const float* w = weight.ptr<float>(y);
    for (int x = 0; x < value.cols; ++x) {
      const float divisor = std::max(w[x], least);
      for (int c = 0; c < channels; ++c) v[x * channels + c] /= divisor;
    }
  }
}

}  // namespace facecap
