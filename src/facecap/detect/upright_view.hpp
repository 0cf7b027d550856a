#pragma once
// A frame turned so that a face rolled by some angle in it stands upright:
// dlib's HOG detector and its landmark cascade were trained on faces within
// about 40 degrees of upright, and lose a head tilted further (someone lying
// down, a camera on its side). FaceTracker follows such a face in the frame
// turned by a multiple of 45 degrees.
//
// Image coordinates, y down: a face whose eye line (iBUG 36 to 45) points
// `degrees` clockwise of the x axis in the frame points along it in the
// view. The view holds the whole frame (its canvas grows to the turned
// frame's bounding box), scaled by `scale`.
#include <opencv2/core.hpp>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

// The eye line's angle in the image (iBUG 36 to 45), degrees clockwise of
// the x axis, in (-180, 180]: 0 for an upright face.
float roll_degrees(const Landmarks& lm);

class UprightView {
 public:
  // The frame itself (no copy) for 0 degrees at scale 1.
  UprightView(const cv::Mat& frame, float degrees, float scale = 1.0f);
  // The mapping alone, for a frame of `frame_size`: no image.
  UprightView(cv::Size frame_size, float degrees, float scale = 1.0f);

  const cv::Mat& image() const { return image_; }
  cv::Size size() const { return size_; }
  float degrees() const { return degrees_; }

  Vec2f to_view(const Vec2f& frame_point) const;
  Vec2f to_frame(const Vec2f& view_point) const;
  Landmarks to_view(const Landmarks& lm) const;
  Landmarks to_frame(const Landmarks& lm) const;
  // The axis-aligned box around a box's turned corners.
  Box to_view(const Box& box) const;
  Box to_frame(const Box& box) const;

 private:
  float degrees_;
  bool identity_;  // upright at full size: points map to themselves, exactly
  cv::Size size_;
  cv::Mat image_;
  Eigen::Matrix2f turn_;  // view = turn_ (frame - frame_centre_) + view_centre_
  Vec2f frame_centre_, view_centre_;
};

// A box of the same size centred where `box`'s centre in view `from` lies in
// view `to` (two views of one frame; the frame itself is the view at 0).
Box carried(const Box& box, const UprightView& from, const UprightView& to);

}  // namespace facecap
