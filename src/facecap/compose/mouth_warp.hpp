#pragma once
// The source frame's openings in the face warped to their new contours
// (§5.3.3 for the mouth; the eyes as a departure): each contour is
// triangulated as a fan around a centre and each triangle mapped affinely
// from its source position to its new one.
#include <opencv2/core.hpp>
#include <vector>

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
// middle holds still, what lies above it (the iris's top, the white)
// stretches up with the lid. Only pixels the layer's mask left unset (not
// the re-rendered skin) are painted, and their mask set. Without it, a lid
// raised by eyeWide showed the frame's own lid again beneath it.
void widen_opening(const cv::Mat& source, const std::vector<cv::Point2f>& source_contour,
                   const std::vector<cv::Point2f>& new_contour, FaceLayer& layer);

}  // namespace facecap
