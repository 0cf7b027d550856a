#pragma once
// Background warp of §6.3: the target frame is cut into triangles between
// the projections of anchor vertices (landmarks and the face boundary), a
// ring of fixed points around them and the border of a surrounding window,
// and each triangle is mapped affinely from where the target face has those
// vertices to where the swapped face has them, so that a wider or narrower
// face does not leave the old one showing. The ring (kRingPoints points at
// kRingScale times the anchors' largest distance from their centre, inside
// the window) holds still: the warp fades out over a band around the face
// and the background beyond it is left as it was (without the ring, the
// bookshelf behind a speaker bent by 5 grey levels on average, 40 px and more
// from the face). The Delaunay triangulation is computed once (the topology
// of the face is fixed) and cached.
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

  std::vector<cv::Vec3i> triangles_;  // indices into the anchors, then the ring, then the 8 border points
  cv::Mat map_x_, map_y_;
};

// The 8 border points of a window (corners and edge midpoints), which stay put.
std::vector<cv::Point2f> window_border(const cv::Rect& window);

constexpr int kRingPoints = 24;
constexpr float kRingScale = 1.3f;
// The fixed ring around both anchor sets: centred on the `from` anchors'
// centroid, kRingScale times the largest anchor distance (of `from` or `to`)
// from it, each point pulled inside the window by 2 px where it would leave it.
std::vector<cv::Point2f> fixed_ring(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                                    const cv::Rect& window);

}  // namespace facecap
