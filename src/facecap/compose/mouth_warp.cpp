#include "facecap/compose/mouth_warp.hpp"

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

cv::Point2f centroid(const std::vector<cv::Point2f>& points) {
  cv::Point2f c(0, 0);
  for (const cv::Point2f& p : points) c += p / float(points.size());
  return c;
}

// Maps the fan of `from` around `from_centre` onto the fan of `to` around
// `to_centre`, triangle by triangle, into the layer; where `under_skin`,
// only into pixels the layer's mask left unset before the fan (a triangle's
// own mask evaluated after its neighbours painted lost the widening:
// address_720p_a to surprise, 45 frames, eye_opening_change -0.002 against
// 0.065), and triangles whose corners all stay are left as they are.
void warp_fan(const cv::Mat& source, const std::vector<cv::Point2f>& from, cv::Point2f from_centre,
              const std::vector<cv::Point2f>& to, cv::Point2f to_centre, bool under_skin, FaceLayer& layer) {
  const size_t n = from.size();
  const cv::Point2f offset(float(layer.box.x), float(layer.box.y));
  const cv::Mat unset = under_skin ? layer.mask == 0 : cv::Mat();
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    if (under_skin && from_centre == to_centre && from[i] == to[i] && from[j] == to[j]) continue;
    const cv::Point2f src[3] = {from_centre, from[i], from[j]};
    const cv::Point2f dst[3] = {to_centre - offset, to[i] - offset, to[j] - offset};
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
    if (under_skin) triangle &= unset(box);
    patch.copyTo(layer.colour(box), triangle);
    cv::Mat mask = layer.mask(box);
    cv::bitwise_or(mask, triangle, mask);
  }
}

}  // namespace

void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                FaceLayer& layer) {
  if (from.size() < 3 || to.size() != from.size() || layer.box.area() == 0) return;
  warp_fan(source, from, centroid(from), to, centroid(to), false, layer);
}

void widen_opening(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                   FaceLayer& layer) {
  if (from.size() < 3 || to.size() != from.size() || layer.box.area() == 0) return;
  const cv::Point2f centre = centroid(from);
  std::vector<cv::Point2f> wider = from;
  for (size_t i = 0; i < from.size(); ++i) {
    if (cv::norm(to[i] - centre) > cv::norm(from[i] - centre)) wider[i] = to[i];
  }
  warp_fan(source, from, centre, wider, centre, true, layer);
}

}  // namespace facecap
