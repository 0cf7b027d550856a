#pragma once
// The mouth interior of the source frame warped to the new lip contour
// (§5.3.3): the inner lip contour is triangulated (a fan around its centre)
// and each triangle is mapped affinely from its source position to its new one.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/compose/face_layer.hpp"

namespace facecap {

// Paints the warped mouth into the layer (contours in frame pixels) and sets its mask there.
void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& source_contour,
                const std::vector<cv::Point2f>& new_contour, FaceLayer& layer);

}  // namespace facecap
