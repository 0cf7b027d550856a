#include "facecap/compose/mouth_warp.hpp"

#include <opencv2/imgproc.hpp>

namespace facecap {

void warp_mouth(const cv::Mat& source, const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                FaceLayer& layer) {
  const size_t n = from.size();
  if (n < 3 || to.size() != n || layer.box.area() == 0) return;
  const cv::Point2f offset(float(layer.box.x), float(layer.box.y));
  cv::Point2f cf(0, 0), ct(0, 0);
  for (size_t i = 0; i < n; ++i) cf += from[i] / float(n), ct += to[i] / float(n);
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

}  // namespace facecap
