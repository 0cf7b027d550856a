#pragma once
// The source frame's openings in the face warped to their new contours
// (§5.3.3 for the mouth; the eyes as a departure): each contour is
// triangulated as a fan around a centre and each triangle mapped affinely
// from its source position to its new one.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/compose/eye_source.hpp"
#include "facecap/compose/face_layer.hpp"

namespace facecap {

// Paints the warped mouth into the layer (contours in frame pixels, the fan
// around each contour's centroid) and sets its mask there.
void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& source_contour,
                const std::vector<cv::Point2f>& new_contour, FaceLayer& layer);

// An eye's opening stretched into what the new lids open beyond the old
// ones (contours: the skin's loop there, eye_margins.hpp): each contour
// point goes to its new position where that lies farther from the source
// contour's centroid than its old one, and stays where it does not (the
// re-rendered lid covers what a closing lid hides, as a real lid does,
// rather than the eye being squashed). The fan's centre stays: the eye's
// middle holds still, and what lies above it stretches up with the lid.
// With `eye`, neither the iris nor the lid's edge does (WidenedEye,
// eye_source.hpp): the lid's edge and lashes move up whole, the eye the
// frame showed stays, and the eye the lid uncovers shows the iris round and
// the white beside it (stretched, a widened iris came out taller than
// round, and the lash line twice as thick). Only pixels the layer's mask
// left unset (not the re-rendered skin) are painted, and their mask set.
// Without the widening, a lid raised by eyeWide showed the frame's own lid
// again beneath it.
void widen_opening(const cv::Mat& source, const std::vector<cv::Point2f>& source_contour,
                   const std::vector<cv::Point2f>& new_contour, FaceLayer& layer, const VisibleEye* eye = nullptr);

}  // namespace facecap
