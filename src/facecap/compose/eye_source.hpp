#pragma once
// Where an eye's pixels come from when its upper lid rises (widen_opening,
// mouth_warp.hpp): the lid's edge moves up whole, what the frame showed of
// the eye stays, and the eye the lid uncovers is drawn from what the frame
// shows of it, the iris round and without a second catchlight.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace facecap {

// What the frame shows of an eye, for widen_opening: the dark disc of its
// iris (iris.hpp) and its opening between the lids as the landmarks mark
// it (iBUG 36-41 or 42-47), in frame pixels.
struct VisibleEye {
  cv::Point2f iris_centre;
  float iris_radius = 0.0f;
  std::vector<cv::Point2f> opening;
};

// An eye being widened: what the frame (`source`, 8-bit BGR) shows of it,
// and the skin's loop around it before (`from`) and after (`wider`), in
// frame pixels. Holds references to all four: they must outlive it. The
// eye's opening needs 3 points or more.
class WidenedEye {
 public:
  WidenedEye(const cv::Mat& source, const VisibleEye& eye, const std::vector<cv::Point2f>& from,
             const std::vector<cv::Point2f>& wider);

  // Where output pixel `p` takes its colour from, given where the fan
  // (widen_opening) would take it from. Where the upper lid rose, its edge
  // band (the lid's rim and lashes, between the skin's loop and the
  // landmarks' opening) moves up whole with it, along the eye's
  // up-direction, as far as the loop rose there (stretched by the fan, it
  // came out twice as thick); what the frame showed of the eye stays where
  // it was; between them lies the eye the lid uncovered. Elsewhere (a lower
  // lid lowered, the corners) the fan moves the lid, and the eye it
  // uncovers is drawn the same way.
  cv::Point2f source_of(const cv::Point2f& p, const cv::Point2f& fan) const;

 private:
  // The eye's own axes: across through its corners, up perpendicular to
  // it, toward the lid that moved out (whatever the face's roll).
  struct Axes {
    cv::Point2f centre, across, up;
    float u(const cv::Point2f& p) const { return (p - centre).dot(across); }
    float v(const cv::Point2f& p) const { return (p - centre).dot(up); }
  };

  float depth_in(const cv::Point2f& s) const;
  bool inside(const cv::Point2f& s, float margin = 0.0f) const;
  bool clear(const cv::Point2f& s) const { return inside(s, edge_); }
  bool glint(const cv::Point2f& s) const;
  bool catchlight(const cv::Point2f& s) const;
  float bright_lid_luma() const;
  bool above_middle(const cv::Point2f& s) const;
  float rise(const cv::Point2f& p) const;
  cv::Point2f uncovered(const cv::Point2f& p, const cv::Point2f& below) const;

  const cv::Mat& source_;
  const VisibleEye& eye_;
  const std::vector<cv::Point2f>& from_;
  const std::vector<cv::Point2f>& wider_;
  Axes axes_;
  float edge_;                                 // the lid's edge and the iris's blurred rim, px
  float iris_luma_;                            // the iris's own brightness (its median)
  std::optional<cv::Point2f> iris_median_at_;  // a pixel of the iris that bright
  float lid_luma_ = 255.0f;                    // the lid's bright skin (bright_lid_luma)
};

}  // namespace facecap
