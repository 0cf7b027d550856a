#include "facecap/compose/eye_source.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>

#include "facecap/core/statistics.hpp"

namespace facecap {

namespace {

// A catchlight and its blurred halo, against the iris's median brightness.
// On address_720p_a's dark irises: median 38-40, 90th percentile 56-60,
// 97th 60-79, catchlights up to 235; at 60, the halo (70-95) came through
// as faint speckles in an iris a lid uncovered far (AU5 at 5).
constexpr float kGlintAboveIris = 30.0f;

// Whether a pixel at `level` is as bright as a catchlight in an iris whose
// median is `iris_luma`.
bool glint_bright(float level, float iris_luma) { return level > iris_luma + kGlintAboveIris; }

// Where the line up through `u` across the eye meets a closed contour: the
// height (v) of its highest crossing (`highest`) or its lowest; none where
// it misses.
template <class Axes>
std::optional<float> crossing(const std::vector<cv::Point2f>& contour, const Axes& axes, float u, bool highest) {
  std::optional<float> found;
  for (size_t i = 0; i < contour.size(); ++i) {
    const cv::Point2f& a = contour[i];
    const cv::Point2f& b = contour[(i + 1) % contour.size()];
    const float ua = axes.u(a), ub = axes.u(b);
    if (ua == ub || (u < ua && u < ub) || (u > ua && u > ub)) continue;
    const float v = axes.v(a) + (u - ua) / (ub - ua) * (axes.v(b) - axes.v(a));
    if (!found || (highest ? v > *found : v < *found)) found = v;
  }
  return found;
}

// A pixel's brightness (BT.601 luma) in an 8-bit BGR frame.
float luma(const cv::Mat& frame, int x, int y) {
  const cv::Vec3b& c = frame.at<cv::Vec3b>(std::clamp(y, 0, frame.rows - 1), std::clamp(x, 0, frame.cols - 1));
  return 0.114f * c[0] + 0.587f * c[1] + 0.299f * c[2];
}

// A pixel of median brightness (BT.601 luma) among those `use` accepts in
// the disc of `radius` around `centre`, within `bounds`, and that
// brightness; none where it accepts none.
template <class Accept>
std::optional<std::pair<cv::Point2f, float>> median_pixel(const cv::Mat& frame, const cv::Point2f& centre, float radius,
                                                          const cv::Rect& bounds, const Accept& use) {
  std::vector<std::pair<float, cv::Point2f>> levels;
  const int y0 = std::max(cvFloor(centre.y - radius), bounds.y),
            y1 = std::min(cvCeil(centre.y + radius), bounds.br().y);
  const int x0 = std::max(cvFloor(centre.x - radius), bounds.x),
            x1 = std::min(cvCeil(centre.x + radius), bounds.br().x);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const cv::Point2f s{float(x), float(y)};
      if ((s - centre).dot(s - centre) <= radius * radius && use(s)) levels.emplace_back(luma(frame, x, y), s);
    }
  if (levels.empty()) return std::nullopt;
  const auto middle = levels.begin() + levels.size() / 2;
  std::nth_element(levels.begin(), middle, levels.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return std::pair{middle->second, middle->first};
}

}  // namespace

WidenedEye::WidenedEye(const cv::Mat& source, const VisibleEye& eye, const std::vector<cv::Point2f>& from,
                       const std::vector<cv::Point2f>& wider)
    : source_(source), eye_(eye), from_(from), wider_(wider) {
  // The corners: the two points of the opening farthest apart.
  cv::Point2f a = eye.opening[0], b = eye.opening[0];
  for (const cv::Point2f& p : eye.opening)
    for (const cv::Point2f& q : eye.opening)
      if ((q - p).dot(q - p) > (b - a).dot(b - a)) a = p, b = q;
  axes_.centre = 0.5f * (a + b);
  axes_.across = (b - a) / std::max(1e-6f, float(cv::norm(b - a)));
  // Up: toward the lid that moved out (the upper one, whatever the face's
  // roll; on a tie, the frame's top).
  axes_.up = {axes_.across.y, -axes_.across.x};
  float outward = 0.0f;
  for (size_t i = 0; i < from.size() && i < wider.size(); ++i) outward += (wider[i] - from[i]).dot(axes_.up);
  if (outward < 0.0f || (outward == 0.0f && axes_.up.y > 0)) axes_.up = -axes_.up;
  // Some 2 px at 720p, where an iris is 9-10 px across.
  edge_ = std::max(1.5f, 0.1f * eye.iris_radius);
  iris_luma_ = 255.0f;
  if (source.type() == CV_8UC3) {
    const auto median = median_pixel(source, eye.iris_centre, eye.iris_radius - edge_,
                                     cv::boundingRect(eye.opening),  // only the opening can be clear
                                     [&](const cv::Point2f& s) { return clear(s); });
    if (median) iris_median_at_ = median->first, iris_luma_ = median->second;
    lid_luma_ = bright_lid_luma();
  }
}

// The lid's bright skin: the 90th percentile of the brightness between the
// skin's loop and the lids' line, above the opening's middle (its lashes
// and its pale wet rim lie below that), on every other pixel of every other
// row (a quarter of the cost, the same percentile to a level or two); 255
// where none shows.
float WidenedEye::bright_lid_luma() const {
  std::vector<float> levels;
  const cv::Rect box = cv::boundingRect(from_) & cv::Rect(0, 0, source_.cols, source_.rows);
  for (int y = box.y; y < box.br().y; y += 2)
    for (int x = box.x; x < box.br().x; x += 2) {
      const cv::Point2f s{float(x), float(y)};
      // The loop's test first: it needs no distance, and it rules out the box's corners.
      if (cv::pointPolygonTest(from_, s, false) >= 0 && !inside(s, -1.0f) && above_middle(s))
        levels.push_back(luma(source_, x, y));
    }
  return levels.empty() ? 255.0f : quantile(levels, 0.9f);
}

// Whether the frame shows a catchlight at pixel `s` itself: brighter than
// the iris by the glint's margin and than the lid's bright skin, which a
// lid's pale rim is not.
bool WidenedEye::catchlight(const cv::Point2f& s) const {
  if (source_.type() != CV_8UC3) return false;
  const float level = luma(source_, cvRound(s.x), cvRound(s.y));
  return glint_bright(level, iris_luma_) && level > lid_luma_;
}

// How far `s` lies inside the landmarks' opening (negative: outside).
float WidenedEye::depth_in(const cv::Point2f& s) const { return float(cv::pointPolygonTest(eye_.opening, s, true)); }

// Whether `s` lies inside the landmarks' opening by `margin` or more (clear:
// by the edge, where the frame shows the eye).
bool WidenedEye::inside(const cv::Point2f& s, float margin) const { return depth_in(s) >= margin; }

// Whether what the frame shows at `s` (the four pixels it is interpolated
// from) holds a catchlight: a reflection on the cornea, far brighter than
// the iris. Copied into the iris a lid uncovers, it would show twice.
bool WidenedEye::glint(const cv::Point2f& s) const {
  if (source_.type() != CV_8UC3) return false;
  const int x = cvFloor(s.x), y = cvFloor(s.y);
  for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}})
    if (glint_bright(luma(source_, x + dx, y + dy), iris_luma_)) return true;
  return false;
}

// Whether `s` lies above the opening's middle where it is across the eye.
bool WidenedEye::above_middle(const cv::Point2f& s) const {
  const float u = axes_.u(s);
  const std::optional<float> top = crossing(eye_.opening, axes_, u, true);
  const std::optional<float> bottom = crossing(eye_.opening, axes_, u, false);
  return top && bottom && axes_.v(s) > 0.5f * (*top + *bottom);
}

// How far the upper lid rose where `p` is across the eye (0 where it did not).
float WidenedEye::rise(const cv::Point2f& p) const {
  const float u = axes_.u(p);
  const std::optional<float> old_top = crossing(from_, axes_, u, true), new_top = crossing(wider_, axes_, u, true);
  return old_top && new_top ? std::max(0.0f, *new_top - *old_top) : 0.0f;
}

// Where output pixel `p`, which a raised lid uncovered, takes the eye
// from (`below`: the pixel the eye's content there would come from if it
// moved as the lid did): the iris where the frame shows it clear of the
// lids, at the pixel itself, else (not a catchlight) its mirror image
// across the disc's diameter along the eye (through its corners), or at the
// same distance from the centre turned toward a corner; off the disc, where
// `below` lies on it (or on its edge), the white as far outside the disc as
// the pixel is, on `below`'s row across the eye or, above the disc, turned
// toward a corner; else `below`. All in the eye's own axes: a face rolled
// in the frame gets what an upright one does.
cv::Point2f WidenedEye::uncovered(const cv::Point2f& p, const cv::Point2f& below) const {
  const float r = eye_.iris_radius;
  const cv::Point2f c = eye_.iris_centre;
  // In the eye's axes from the iris's centre: across (du) and up (dv).
  const auto at = [&](float du, float dv) { return c + du * axes_.across + dv * axes_.up; };
  const float du = (p - c).dot(axes_.across), dv = (p - c).dot(axes_.up);
  const float from_centre = std::hypot(du, dv);
  const float side = du >= 0 ? 1.0f : -1.0f;  // p's side of the iris
  // The first point at `radius` from the iris's centre that `usable`
  // accepts, turning from p's direction toward the eye's corner on p's side.
  const auto turned_to_the_side = [&](float radius, const auto& usable) -> std::optional<cv::Point2f> {
    const float angle = std::atan2(dv, side * du);
    for (int step = 1; step <= 8; ++step) {
      const float turned = angle * (1.0f - step / 8.0f);
      const cv::Point2f q = at(side * radius * std::cos(turned), radius * std::sin(turned));
      if (usable(q)) return q;
    }
    return std::nullopt;
  };
  const auto white = [&](const cv::Point2f& s) { return clear(s); };
  if (from_centre <= r) {
    if (clear(p)) return p;
    // The iris elsewhere, but not its catchlights.
    const auto iris = [&](const cv::Point2f& s) { return clear(s) && !glint(s); };
    const cv::Point2f mirrored = at(du, -dv);
    if (iris(mirrored)) return mirrored;
    // Under both lids: the iris at the same distance from its centre (off
    // its blurred rim), turned toward the side (the iris is much the same
    // all round; moved with the lid, a pupil would be drawn stretched here).
    if (const auto turned = turned_to_the_side(std::max(0.0f, std::min(from_centre, r - edge_)), iris)) return *turned;
    // Catchlights all round (a small iris, its lights under the lid): the
    // iris below if it is none, else the iris's median pixel.
    if (iris(below)) return below;
    return iris_median_at_.value_or(below);
  }
  const float rim = r + edge_, row = (below - c).dot(axes_.up);
  if (std::abs(row) >= rim) return below;
  const float half_chord = std::sqrt(rim * rim - row * row);
  if (std::abs((below - c).dot(axes_.across)) >= half_chord) return below;
  const cv::Point2f beside = at(side * (half_chord + (from_centre - r)), row);
  if (white(beside)) return beside;
  // Above the disc, where that row shows no white: the white as far out
  // from the disc, turned toward the side.
  return turned_to_the_side(from_centre + edge_, white).value_or(below);
}

cv::Point2f WidenedEye::source_of(const cv::Point2f& p, const cv::Point2f& fan) const {
  const float lid_rise = rise(p);
  if (lid_rise > 0) {
    const cv::Point2f lowered = p - lid_rise * axes_.up;
    // The band, to a pixel off the opening: what the pixel's interpolation
    // reaches of the eye below it (a catchlight under the lid's edge) would
    // come up with the lid and show twice.
    const bool lowered_near_eye = depth_in(lowered) >= -1.0f;
    if (!lowered_near_eye && above_middle(lowered)) return lowered;
    // What the frame showed of the eye stays, off the lid's edge: the
    // edge's blur (lashes, the lid's pale wet rim) would stay behind as a
    // second line, across the white and the iris. But a catchlight just
    // under the lid's line stays: it is on the cornea, and the eye looks
    // dull without it.
    const float p_depth = depth_in(p);
    if (p_depth >= edge_ || (p_depth >= 0.0f && catchlight(p))) return p;
    if (lowered_near_eye) return uncovered(p, lowered);
  }
  if (!clear(fan)) return fan;
  return uncovered(p, fan);
}

}  // namespace facecap
