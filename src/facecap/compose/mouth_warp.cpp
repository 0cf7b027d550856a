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

// Barycentric weights of `p` in the triangle (a, b, c); false where it
// lies outside (by more than `slack` of the triangle's own weights) or the
// triangle has no area.
bool barycentric(const cv::Point2f& p, const cv::Point2f& a, const cv::Point2f& b, const cv::Point2f& c,
                 cv::Vec3f& weights, float slack = 1e-4f) {
  const cv::Point2f ab = b - a, ac = c - a, ap = p - a;
  const float area = ab.cross(ac);
  if (std::abs(area) < 1e-6f) return false;
  const float wb = ap.cross(ac) / area, wc = ab.cross(ap) / area;
  weights = {1 - wb - wc, wb, wc};
  return weights[0] >= -slack && wb >= -slack && wc >= -slack;
}

}  // namespace

void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                FaceLayer& layer) {
  const size_t n = from.size();
  if (n < 3 || to.size() != n || layer.box.area() == 0) return;
  const cv::Point2f offset(float(layer.box.x), float(layer.box.y));
  const cv::Point2f cf = centroid(from), ct = centroid(to);
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2f src[3] = {cf, from[i], from[(i + 1) % n]};
    const cv::Point2f dst[3] = {ct - offset, to[i] - offset, to[(i + 1) % n] - offset};
    const cv::Rect box =
        cv::boundingRect(std::vector<cv::Point2f>(dst, dst + 3)) & cv::Rect(0, 0, layer.box.width, layer.box.height);
    if (box.area() == 0) continue;
    // Source frame pixels to this triangle's box in the layer.
    cv::Mat affine = cv::getAffineTransform(src, dst);
    affine.at<double>(0, 2) -= box.x;
    affine.at<double>(1, 2) -= box.y;
    cv::Mat patch;
    cv::warpAffine(source, patch, affine, box.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    cv::Mat triangle(box.size(), CV_8U, cv::Scalar(0));
    std::vector<cv::Point> pts;
    for (const cv::Point2f& p : dst) pts.emplace_back(cvRound(p.x - box.x), cvRound(p.y - box.y));
    cv::fillConvexPoly(triangle, pts, cv::Scalar(255), cv::LINE_AA);
    patch.copyTo(layer.colour(box), triangle);
    cv::Mat mask = layer.mask(box);
    cv::bitwise_or(mask, triangle, mask);
  }
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
      for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        cv::Vec3f w;
        if (!barycentric(p, centre, wider[i], wider[j], w)) continue;
        if (wider[i] == from[i] && wider[j] == from[j]) break;  // this part of the eye stays
        const cv::Point2f fan = w[0] * centre + w[1] * from[i] + w[2] * from[j];
        const cv::Point2f q = widened ? widened->source_of(p, fan) : fan;
        map_x.at<float>(y, x) = q.x;
        map_y.at<float>(y, x) = q.y;
        painted.at<uchar>(y, x) = 255;
        break;
      }
    }
  }
  cv::Mat patch;
  cv::remap(source, patch, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  patch.copyTo(layer.colour(box), painted);
  cv::Mat mask = layer.mask(box);
  cv::bitwise_or(mask, painted, mask);
}

}  // namespace facecap
