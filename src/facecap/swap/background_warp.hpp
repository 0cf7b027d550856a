#pragma once
// Background warp of §6.3: the target frame is cut into triangles between
// the projections of anchor vertices (landmarks and the face boundary) and
// the corners of a surrounding window, and each triangle is mapped affinely
// from where the target face has those vertices to where the swapped face
// has them, so that a wider or narrower face does not leave the old one
// showing. The Delaunay triangulation is computed once (the topology of the
// face is fixed) and cached.
#include <opencv2/core.hpp>
#include <vector>

namespace facecap {

class BackgroundWarp {
 public:
  // Warps `frame` inside `window` (clipped to the frame) so that the
  // anchors move from `from` to `to`; writes the window-sized result. The
  // first call triangulates `from` together with the window's border.
  void warp(const cv::Mat& frame, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
            cv::Rect window, cv::Mat& out);

  int triangle_count() const { return static_cast<int>(triangles_.size()); }

 private:
  void triangulate(const std::vector<cv::Point2f>& points, const cv::Rect& window);

  std::vector<cv::Vec3i> triangles_;  // indices into anchors followed by the 8 border points
  cv::Mat map_x_, map_y_;
};

// The 8 border points of a window (corners and edge midpoints), which stay put.
std::vector<cv::Point2f> window_border(const cv::Rect& window);

}  // namespace facecap
