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

// What the frame shows of an eye, for widen_opening: the dark disc of its
// iris (iris.hpp) and its opening between the lids as the landmarks mark
// it (iBUG 36-41 or 42-47), in frame pixels.
struct VisibleEye {
  cv::Point2f iris_centre;
  float iris_radius = 0.0f;
  std::vector<cv::Point2f> opening;
};

// An eye's opening stretched into what the new lids open beyond the old
// ones (contours: the skin's loop there, eye_margins.hpp): each contour
// point goes to its new position where that lies farther from the source
// contour's centroid than its old one, and stays where it does not (the
// re-rendered lid covers what a closing lid hides, as a real lid does,
// rather than the eye being squashed). The fan's centre stays: the eye's
// middle holds still, and what lies above it stretches up with the lid.
// With `eye`, the iris does not: the fan moves the lid's edge and the
// lashes, but a pixel of the iris's disc shows the iris as it lies (from
// below the lid, the disc's mirror image across its horizontal diameter),
// and a pixel beside the disc the white of the eye beside it (without it,
// a widened iris came out taller than round). Only pixels the layer's mask
// left unset (not the re-rendered skin) are painted, and their mask set.
// Without the widening, a lid raised by eyeWide showed the frame's own lid
// again beneath it.
void widen_opening(const cv::Mat& source, const std::vector<cv::Point2f>& source_contour,
                   const std::vector<cv::Point2f>& new_contour, FaceLayer& layer, const VisibleEye* eye = nullptr);

}  // namespace facecap
