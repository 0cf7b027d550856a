#pragma once
// The piecewise-affine map of §6.3's background warp: the Delaunay
// triangulation of the destination points, each destination triangle
// mapped affinely onto its source triangle. It carries what lies between
// neighbouring points along the straight segments between them, as a mesh's
// edges do; background_warp.hpp uses it around the eyes and the mouth.
#include <opencv2/core.hpp>
#include <vector>

namespace facecap {

class PiecewiseAffineMap {
 public:
  // Triangulates `dst`, which should tile the window (its corners among the
  // points); `src` are the same points' sources.
  PiecewiseAffineMap(std::vector<cv::Point2f> src, std::vector<cv::Point2f> dst, const cv::Rect& window);

  // Writes, for the pixels of `region` (a rectangle of window coordinates)
  // that a triangle covers, the source position (frame coordinates) that
  // each maps to, into map_x and map_y (CV_32F, the region's size: their
  // (x, y) is the window's pixel region.tl() + (x, y)); other pixels are
  // left as they were.
  void fill(const cv::Rect& region, cv::Mat& map_x, cv::Mat& map_y) const;

 private:
  std::vector<cv::Point2f> src_, dst_;
  cv::Rect window_;
  std::vector<cv::Vec3i> triangles_;
};

// The 8 border points of a window (corners and edge midpoints).
std::vector<cv::Point2f> window_border(const cv::Rect& window);

}  // namespace facecap
