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
// from the face).
//
// Departure from §6.3, which triangulates the target's points once and
// keeps that topology: here the Delaunay triangulation is of the destination
// points, each frame. As the head turns, and where the new face's shape
// differs from the target's, anchors move past their neighbours, and a
// triangle laid out on the target's points turns over in the destination:
// it overlaps its neighbours and leaves pixels that no triangle covers,
// which kept the unwarped frame (the old cheek in notches beside the new
// jaw). Triangles of the destination tile the window whatever the anchors
// do, so the map is continuous; where the source points of one have
// crossed, its content is mirrored instead, which anchors_facing() keeps
// rare. The share of the window's pixels where the map jumps more than 4 px
// to a neighbour (200 frames, with anchors_facing()): Biden into
// emotions_pexels 0.134 % -> 0.010 %, into address_720p_b 0.090 % -> 0.000 %.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/geometry.hpp"

namespace facecap {

class BackgroundWarp {
 public:
  // Warps `frame` inside `window` (clipped to the frame) so that the
  // anchors move from `from` to `to`; writes the window-sized result. An
  // anchor outside the window in either set is left out: the window's
  // border holds still.
  void warp(const cv::Mat& frame, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
            cv::Rect window, cv::Mat& out);

  // The last warp's triangles.
  int triangle_count() const { return static_cast<int>(triangles_.size()); }

 private:
  void triangulate(const std::vector<cv::Point2f>& points, const cv::Rect& window);

  std::vector<cv::Vec3i> triangles_;  // indices into the kept anchors, then the ring, then the 8 border points
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

// Which anchors (vertex indices; those from `skin_vertices` on, which have
// no normal here, are kept) face the camera in both the target's mesh and
// the swapped one (camera space, with their vertex normals). One turned
// away lies behind its face's visible surface: its projection falls inside
// the outline, or across it past the anchors on the outline, and the
// triangles between them turn over. With the destination triangulation
// alone, such triangles squeezed the target's outline against the new one:
// the seam ratio of Obama into address_720p_b (eval swap, 30 frames) went
// 1.49 -> 1.54; leaving these anchors out too, 1.41 (whole clip 1.175 ->
// 1.169). Leaving out also those that merely graze (facing under 0.1-0.3)
// raised Biden into address_720p_a's (whole clip 0.99 -> 1.07).
std::vector<bool> anchors_facing(const std::vector<int>& anchors, const Positions& target_points,
                                 const Positions& target_normals, const Positions& swapped_points,
                                 const Positions& swapped_normals, int skin_vertices);

}  // namespace facecap
