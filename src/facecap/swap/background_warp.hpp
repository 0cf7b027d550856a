#pragma once
// Background warp of §6.3: the target frame is moved so that the
// projections of anchor vertices (landmarks and the face boundary) go from
// where the target face has them to where the swapped face has them, so
// that a wider or narrower face does not leave the old one showing. A ring
// of fixed points (kRingPoints points at kRingScale times the anchors'
// largest distance from their centre, inside the window) holds still, and
// the background beyond a second such ring (kOuterRingScale) is left as it
// was: the warp fades out over a band around the face (without the ring,
// the bookshelf behind a speaker bent by 5 grey levels on average, 40 px
// and more from the face).
//
// Departure from §6.3, which maps the triangles between those points
// affinely, with the topology of the target's first frame: here the map is
// a thin-plate spline through them (Bookstein 1989), fitted each frame. An
// affine map per triangle is continuous but creased along every edge, and
// between the outline and the ring the triangles are long slivers fanning
// out from a few ring points: where neighbouring anchors move differently
// (the temple of a narrower face), strands of hair crossing them bent into
// zigzags. The spline is smooth everywhere and exact at the anchors. Over
// 120 frames of Obama's portrait into emotions_pexels / address_720p_b:
// share of the window's pixels whose map bends by more than 0.5 px from
// one pixel to the next (second difference) 0.78 % / 0.16 % -> 0.012 % /
// 0.002 %; the largest such bend 18.0 / 14.9 px -> 0.98 / 1.46 px; pixels
// where it jumps more than 4 px (a tear) 0.015 % / 0.002 % -> 0.0004 % /
// 0.0002 %. The triangles, laid out on the target's points, also turned
// over where anchors moved past their neighbours, which the destination's
// Delaunay triangulation had mended since; a spline has no triangles to
// turn.
//
// Around the eyes and the mouth (their landmark outlines grown by
// kFeatureMargin), the triangles' map is kept, mixed into the spline's over
// a feathered edge that lies on the new face's skin: there the target's own
// eyes and mouth show through the new face's openings and the fade at their
// rims, and the triangles carry them along the straight segments between
// the anchors, as the mesh's rims run, where the spline bends between them.
// The re-tracked output's expression correlation with the target (eval
// swap, whole clips) was 0.779 with the triangles everywhere, 0.733 with
// the spline alone and 0.772 with both (Biden into address_720p_a);
// Obama into address_720p_b 0.795 with the spline alone, 0.815 with both.
// The creases come back around the features, under the new face's skin:
// over the 120 frames above, map bends over 0.5 px 0.19 % / 0.040 % of the
// window, the largest 2.1 / 3.1 px; the seam ratios stay the spline's.
#include <Eigen/Core>
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
  // `features` (destination polygons in frame coordinates: the eyes' and
  // the mouth's outlines) keep the triangles' map around them, out to
  // kFeatureMargin times the window's width.
  void warp(const cv::Mat& frame, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
            cv::Rect window, cv::Mat& out, const std::vector<std::vector<cv::Point2f>>& features = {});

  // The last warp's spline control points: the anchors kept and the rings.
  int control_count() const { return static_cast<int>(controls_.rows()); }

 private:
  // Fits the spline through `offsets` at `points`; false where it has no
  // finite solution.
  bool fit(const std::vector<cv::Point2f>& points, const std::vector<cv::Point2f>& offsets);
  // The spline's offset at pixel p; `kernel` is scratch space.
  cv::Point2f offset_at(cv::Point2f p, Eigen::ArrayXf& kernel) const;
  // Mixes the piecewise-affine map of src -> dst (piecewise_affine_map.hpp)
  // into map_x_, map_y_ around the features.
  void keep_triangles_around(const std::vector<std::vector<cv::Point2f>>& features, const std::vector<cv::Point2f>& src,
                             const std::vector<cv::Point2f>& dst, const cv::Rect& window);

  cv::Point2f centre_;
  double scale_ = 1;
  // Per control point: x, y (centred, scaled), weights of the x and y offsets.
  Eigen::Matrix<float, Eigen::Dynamic, 4> controls_;
  float affine_x_[3] = {}, affine_y_[3] = {};
  cv::Mat grid_x_, grid_y_, fine_x_, fine_y_, map_x_, map_y_, pa_x_, pa_y_;
};

// The spline is evaluated on a grid of about this many nodes across the
// window (nodes at most 8 px apart) and interpolated bicubically between.
constexpr int kGridNodesAcross = 48;
constexpr int kRingPoints = 32;
constexpr float kRingScale = 1.3f;
// The second ring, beyond which the offset is zero: between the two the
// spline levels out, so that the warp ends without a crease (cut at the
// first ring, the largest bend there in the tests' narrowed disc was 0.75
// px against 0.38).
constexpr float kOuterRingScale = 1.5f;
// How far around a feature (times the window's width: about 12 px at 720p)
// the triangles' map is kept; see the header's note.
constexpr float kFeatureMargin = 0.025f;
// The centre of the fixed rings: the `from` anchors' centroid.
cv::Point2f ring_centre(const std::vector<cv::Point2f>& from);
// A fixed ring around both anchor sets: centred on ring_centre(from),
// `scale` times the largest anchor distance (of `from` or `to`) from it,
// each point pulled inside the window by 2 px where it would leave it.
std::vector<cv::Point2f> fixed_ring(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                                    const cv::Rect& window, float scale = kRingScale);

// Which anchors (vertex indices; those from `skin_vertices` on, which have
// no normal here, are kept) face the camera in both the target's mesh and
// the swapped one (camera space, with their vertex normals). One turned
// away lies behind its face's visible surface: its projection falls inside
// the outline, or across it past the anchors on the outline, and the
// triangles between them turned over. With the destination triangulation
// alone, such triangles squeezed the target's outline against the new one:
// the seam ratio of Obama into address_720p_b (eval swap, 30 frames) went
// 1.49 -> 1.54; leaving these anchors out too, 1.41 (whole clip 1.175 ->
// 1.169). Leaving out also those that merely graze (facing under 0.1-0.3)
// raised Biden into address_720p_a's (whole clip 0.99 -> 1.07).
std::vector<bool> anchors_facing(const std::vector<int>& anchors, const Positions& target_points,
                                 const Positions& target_normals, const Positions& swapped_points,
                                 const Positions& swapped_normals, int skin_vertices);

}  // namespace facecap
