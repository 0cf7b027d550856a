#include "facecap/swap/colour_change.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// Keeps the log finite on black texels; far below skin's albedo.
constexpr float kLogFloor = 0.02f;

const ColourChangeOptions& checked(const ColourChangeOptions& o) {
  if (!(o.min_log_change > 0 && o.min_extent_mm >= 0 && o.min_weight >= 0))
    throw Error("colour change: needs a positive change, and a width and weight of 0 or more");
  return o;
}

}  // namespace

ColourChange::ColourChange(double texels_per_mm, ColourChangeOptions options)
    : options_(checked(options)), radius_(int(std::lround(0.5 * options_.min_extent_mm * texels_per_mm))) {
  if (!(texels_per_mm > 0)) throw Error("colour change: needs a grid of positive texels per millimetre");
}

void ColourChange::reset() {
  last_log_ = cv::Mat();
  last_weight_ = cv::Mat();
}

bool ColourChange::changed(const FaceTexture& seen, int frame_index) {
  if (!sequence_.follows(frame_index)) reset();
  cv::Mat log_colour;
  cv::log(cv::max(seen.albedo, cv::Scalar::all(0)) + cv::Scalar::all(kLogFloor), log_colour);
  const bool known = !last_log_.empty() && last_log_.size() == log_colour.size();
  cv::Mat moved;
  if (known) {
    moved.create(log_colour.size(), CV_8U);
    for (int y = 0; y < log_colour.rows; ++y) {
      const auto* now = log_colour.ptr<cv::Vec3f>(y);
      const auto* last = last_log_.ptr<cv::Vec3f>(y);
      const float* w_now = seen.weight.ptr<float>(y);
      const float* w_last = last_weight_.ptr<float>(y);
      uchar* m = moved.ptr<uchar>(y);
      for (int x = 0; x < log_colour.cols; ++x) {
        const cv::Vec3f d = now[x] - last[x];
        const float change = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
        m[x] = w_now[x] > options_.min_weight && w_last[x] > options_.min_weight && change > options_.min_log_change
                   ? 255
                   : 0;
      }
    }
    if (radius_ > 0)
      cv::morphologyEx(moved, moved, cv::MORPH_OPEN,
                       cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius_ + 1, 2 * radius_ + 1)));
  }
  last_log_ = log_colour;
  last_weight_ = seen.weight.clone();
  return !known || cv::countNonZero(moved) > 0;
}

}  // namespace facecap
