#include "facecap/compose/mouth_warp.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/compose/eye_source.hpp"

namespace facecap {

namespace {

cv::Point2f centroid(const std::vector<cv::Point2f>& points) {
  cv::Point2f c(0, 0);
  for (const cv::Point2f& p : points) c += p / float(points.size());
  return c;
}

// Barycentric weights of `p` in the triangle (a, b, c), inside it or not;
// none where the triangle has no area.
std::optional<cv::Vec3f> weights_in(const cv::Point2f& p, const cv::Point2f& a, const cv::Point2f& b,
                                    const cv::Point2f& c) {
  const cv::Point2f ab = b - a, ac = c - a, ap = p - a;
  const float area = ab.cross(ac);
  if (std::abs(area) < 1e-6f) return std::nullopt;
  const float wb = ap.cross(ac) / area, wc = ab.cross(ap) / area;
  return cv::Vec3f{1 - wb - wc, wb, wc};
}

// A triangle of a contour's fan around `centre` (centre, contour[i],
// contour[i + 1]) and a point's barycentric weights in it.
struct FanPoint {
  size_t triangle = 0;
  cv::Vec3f weights;
};

// The fan triangle that holds `p` (by `slack` of its own weights), the
// first where triangles overlap; none where no triangle does.
std::optional<FanPoint> in_fan(const cv::Point2f& p, const cv::Point2f& centre, const std::vector<cv::Point2f>& contour,
                               float slack = 1e-4f) {
  for (size_t i = 0; i < contour.size(); ++i) {
    const std::optional<cv::Vec3f> w = weights_in(p, centre, contour[i], contour[(i + 1) % contour.size()]);
    if (w && (*w)[0] >= -slack && (*w)[1] >= -slack && (*w)[2] >= -slack) return FanPoint{i, *w};
  }
  return std::nullopt;
}

// The point of the segment (a, b) nearest `p`: how far along it, 0 to 1.
float along_segment(const cv::Point2f& p, const cv::Point2f& a, const cv::Point2f& b) {
  const cv::Point2f ab = b - a;
  const float length2 = ab.dot(ab);
  return length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0f, 1.0f) : 0.0f;
}

// For `p` beside the fan (a smoothed fill's edge pixel): the point of the
// fan nearest it, as weights in its triangle (on the triangle's nearest
// edge). Through the triangle's own map, unbounded beside it, a sliver (a
// closed mouth's fan) carries such pixels far off: across the lips, from
// the seam. Triangles without area are left out.
std::optional<FanPoint> nearest_in_fan(const cv::Point2f& p, const cv::Point2f& centre,
                                       const std::vector<cv::Point2f>& contour) {
  std::optional<FanPoint> nearest;
  float nearest_distance = 0;
  for (size_t i = 0; i < contour.size(); ++i) {
    const cv::Point2f corners[3] = {centre, contour[i], contour[(i + 1) % contour.size()]};
    if (!weights_in(p, corners[0], corners[1], corners[2])) continue;
    for (int e = 0; e < 3; ++e) {
      const int f = (e + 1) % 3;
      const float t = along_segment(p, corners[e], corners[f]);
      const float distance = float(cv::norm(corners[e] + t * (corners[f] - corners[e]) - p));
      if (nearest && distance >= nearest_distance) continue;
      cv::Vec3f weights(0, 0, 0);
      weights[e] = 1 - t;
      weights[f] = t;
      nearest = FanPoint{i, weights};
      nearest_distance = distance;
    }
  }
  return nearest;
}

// The point at `at`'s weights in the same triangle of another fan.
cv::Point2f on_fan(const FanPoint& at, const cv::Point2f& centre, const std::vector<cv::Point2f>& contour) {
  return at.weights[0] * centre + at.weights[1] * contour[at.triangle] +
         at.weights[2] * contour[(at.triangle + 1) % contour.size()];
}

}  // namespace

void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                FaceLayer& layer) {
  const size_t n = from.size();
  if (n < 3 || to.size() != n || layer.box.area() == 0) return;
  const cv::Point2f cf = centroid(from), ct = centroid(to);
  // The fan's box, its centre counted (which rounding may put a hair
  // outside a contour on one line), so that it holds each triangle's.
  std::vector<cv::Point2f> outline = to;
  outline.push_back(ct);
  const cv::Rect window(0, 0, layer.box.width, layer.box.height);
  const cv::Rect box = (cv::boundingRect(outline) - layer.box.tl()) & window;
  if (box.area() == 0) return;
  // What the fan covers: each triangle's smoothed fill, in its own box.
  cv::Mat painted(box.size(), CV_8U, cv::Scalar(0));
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2f corners[3] = {ct, to[i], to[(i + 1) % n]};
    const cv::Rect own = (cv::boundingRect(std::vector<cv::Point2f>(corners, corners + 3)) - layer.box.tl()) & window;
    if (own.area() == 0) continue;
    cv::Mat triangle(own.size(), CV_8U, cv::Scalar(0));
    std::vector<cv::Point> pts;
    for (const cv::Point2f& p : corners)
      pts.emplace_back(cvRound(p.x - layer.box.x - own.x), cvRound(p.y - layer.box.y - own.y));
    cv::fillConvexPoly(triangle, pts, cv::Scalar(255), cv::LINE_AA);
    cv::Mat covered = painted(own - box.tl());
    cv::bitwise_or(covered, triangle, covered);
  }
  // Each covered pixel from the frame through the fan triangle that holds
  // it, or beside the fan the nearest one: one mapping per pixel, whatever
  // order the triangles come in.
  cv::Mat map_x(box.size(), CV_32F, cv::Scalar(0)), map_y(box.size(), CV_32F, cv::Scalar(0));
  for (int y = 0; y < box.height; ++y)
    for (int x = 0; x < box.width; ++x) {
      if (painted.at<uchar>(y, x) == 0) continue;
      const cv::Point2f p(float(layer.box.x + box.x + x), float(layer.box.y + box.y + y));
      std::optional<FanPoint> at = in_fan(p, ct, to);
      if (!at) at = nearest_in_fan(p, ct, to);
      if (!at) {  // a fan without area: nothing to map through
        painted.at<uchar>(y, x) = 0;
        continue;
      }
      const cv::Point2f q = on_fan(*at, cf, from);
      map_x.at<float>(y, x) = q.x;
      map_y.at<float>(y, x) = q.y;
    }
  cv::Mat patch;
  cv::remap(source, patch, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  patch.copyTo(layer.colour(box), painted);
  cv::Mat mask = layer.mask(box);
  cv::bitwise_or(mask, painted, mask);
}

void widen_opening(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                   FaceLayer& layer, const VisibleEye* eye) {
  const size_t n = from.size();
  if (n < 3 || to.size() != n || layer.box.area() == 0) return;
  const cv::Point2f centre = centroid(from);
  std::vector<cv::Point2f> wider = from;
  bool widens = false;
  for (size_t i = 0; i < n; ++i) {
    if (cv::norm(to[i] - centre) > cv::norm(from[i] - centre)) wider[i] = to[i], widens = true;
  }
  if (!widens) return;
  std::optional<WidenedEye> widened;
  if (eye && eye->opening.size() >= 3) widened.emplace(source, *eye, from, wider);
  // Each unset pixel inside the wider fan, mapped back through the fan
  // triangle that holds it (its barycentric weights on the old corners):
  // one mapping per pixel, whatever order the triangles come in (thin
  // triangles drawn one by one with smoothed edges overlap, and the last
  // drawn won).
  const cv::Point2f offset(float(layer.box.x), float(layer.box.y));
  std::vector<cv::Point2f> outline = wider;
  outline.push_back(centre);
  const cv::Rect box = (cv::boundingRect(outline) - cv::Point(layer.box.x, layer.box.y) + cv::Size(2, 2)) &
                       cv::Rect(0, 0, layer.box.width, layer.box.height);
  if (box.area() == 0) return;
  cv::Mat map_x(box.size(), CV_32F, cv::Scalar(-1)), map_y(box.size(), CV_32F, cv::Scalar(-1));
  cv::Mat painted(box.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < box.height; ++y) {
    const uchar* unset = layer.mask.ptr<uchar>(box.y + y) + box.x;
    for (int x = 0; x < box.width; ++x) {
      if (unset[x] != 0) continue;
      const cv::Point2f p = cv::Point2f(float(box.x + x), float(box.y + y)) + offset;
      const std::optional<FanPoint> at = in_fan(p, centre, wider);
      if (!at) continue;
      const size_t i = at->triangle, j = (i + 1) % n;
      if (wider[i] == from[i] && wider[j] == from[j]) continue;  // this part of the eye stays
      const cv::Point2f fan = on_fan(*at, centre, from);
      const cv::Point2f q = widened ? widened->source_of(p, fan) : fan;
      map_x.at<float>(y, x) = q.x;
      map_y.at<float>(y, x) = q.y;
      painted.at<uchar>(y, x) = 255;
    }
  }
  cv::Mat patch;
  cv::remap(source, patch, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  patch.copyTo(layer.colour(box), painted);
  cv::Mat mask = layer.mask(box);
  cv::bitwise_or(mask, painted, mask);
}

}  // namespace facecap
