#include "facecap/detect/upright_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

namespace facecap {

float roll_degrees(const Landmarks& lm) {
  const Vec2f eyes = lm[45] - lm[36];
  return std::atan2(eyes.y(), eyes.x()) * 180.0f / std::numbers::pi_v<float>;
}

UprightView::UprightView(cv::Size frame_size, float degrees, float scale)
    : degrees_(degrees), identity_(degrees == 0 && scale == 1.0f) {
  // Turning the frame by -degrees (y down: counter-clockwise on screen)
  // brings a line at +degrees to the x axis; exact for quarter turns.
  const float a = -degrees * std::numbers::pi_v<float> / 180.0f;
  const float c = std::round(std::cos(a) * 1e6f) / 1e6f, s = std::round(std::sin(a) * 1e6f) / 1e6f;
  turn_ << scale * c, -scale * s, scale * s, scale * c;
  const float w = float(frame_size.width), h = float(frame_size.height);
  size_ = {std::max(1, int(std::lround(scale * (std::abs(c) * w + std::abs(s) * h)))),
           std::max(1, int(std::lround(scale * (std::abs(s) * w + std::abs(c) * h))))};
  frame_centre_ = {0.5f * (w - 1), 0.5f * (h - 1)};
  view_centre_ = {0.5f * float(size_.width - 1), 0.5f * float(size_.height - 1)};
}

UprightView::UprightView(const cv::Mat& frame, float degrees, float scale) : UprightView(frame.size(), degrees, scale) {
  if (identity_) {
    image_ = frame;
    return;
  }
  // Quarter turns at full size are a transpose and flips.
  const float c = turn_(0, 0), s = turn_(1, 0);
  if (scale == 1.0f && std::abs(c * s) < 1e-6f) {
    if (s > 0.5f) {
      cv::rotate(frame, image_, cv::ROTATE_90_CLOCKWISE);
    } else if (s < -0.5f) {
      cv::rotate(frame, image_, cv::ROTATE_90_COUNTERCLOCKWISE);
    } else {
      cv::rotate(frame, image_, cv::ROTATE_180);
    }
    return;
  }
  const Vec2f offset = view_centre_ - turn_ * frame_centre_;
  const cv::Matx23d affine(turn_(0, 0), turn_(0, 1), offset.x(), turn_(1, 0), turn_(1, 1), offset.y());
  cv::warpAffine(frame, image_, affine, size_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
}

Vec2f UprightView::to_view(const Vec2f& p) const {
  return identity_ ? p : Vec2f(turn_ * (p - frame_centre_) + view_centre_);
}

Vec2f UprightView::to_frame(const Vec2f& p) const {
  return identity_ ? p : Vec2f(turn_.inverse() * (p - view_centre_) + frame_centre_);
}

Landmarks UprightView::to_view(const Landmarks& lm) const {
  Landmarks out;
  for (int i = 0; i < kNumLandmarks; ++i) out[i] = to_view(lm[i]);
  return out;
}

Landmarks UprightView::to_frame(const Landmarks& lm) const {
  Landmarks out;
  for (int i = 0; i < kNumLandmarks; ++i) out[i] = to_frame(lm[i]);
  return out;
}

namespace {

template <typename Map>
Box turned_box(const Box& b, Map map) {
  const Vec2f corners[4] = {map(Vec2f(b.x, b.y)), map(Vec2f(b.x + b.width, b.y)), map(Vec2f(b.x, b.y + b.height)),
                            map(Vec2f(b.x + b.width, b.y + b.height))};
  return bounding_box(std::span<const Vec2f>(corners));
}

}  // namespace

Box UprightView::to_view(const Box& box) const {
  if (identity_) return box;
  return turned_box(box, [this](const Vec2f& p) { return to_view(p); });
}

Box UprightView::to_frame(const Box& box) const {
  if (identity_) return box;
  return turned_box(box, [this](const Vec2f& p) { return to_frame(p); });
}

Box carried(const Box& box, const UprightView& from, const UprightView& to) {
  const Vec2f centre = to.to_view(from.to_frame(box.center()));
  return {centre.x() - 0.5f * box.width, centre.y() - 0.5f * box.height, box.width, box.height};
}

}  // namespace facecap
