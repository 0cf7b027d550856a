#pragma once
// Similarity-aligned face crops (`track --aligned-faces`), the input that
// face recognition and expression networks take: the face rotated upright,
// scaled and moved so that five of its landmarks fall as near as they can
// (least squares over the five, Umeyama's similarity in 2D) on the 5-point
// template of the ArcFace / InsightFace models for a 112x112 crop (Deng et
// al., "ArcFace", CVPR 2019), scaled to the crop's size. The five points
// from the 68: each eye's centre (the mean of its six landmarks), the nose
// tip (30) and the mouth corners (48, 54), in the image's left-to-right order.
#include <array>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

inline constexpr int kAlignedFaceSize = 112;  // the template's own crop

// The template's points for a `size` x `size` crop (pixel centres at integers).
std::array<Vec2f, 5> aligned_face_template(int size);
// The five points of 68 landmarks, in the template's order.
std::array<Vec2f, 5> five_face_points(const Landmarks& lm);

// The similarity (2x3: [s R | t]) that takes image pixels into the crop:
// the least-squares fit of the landmarks' five points onto the template.
Eigen::Matrix<double, 2, 3> aligned_face_transform(const Landmarks& lm, int size);

// The `size` x `size` crop of `image` (any type warpAffine takes), bilinear,
// black where the crop reaches past the image.
cv::Mat aligned_face(const cv::Mat& image, const Landmarks& lm, int size);

}  // namespace facecap
