#include "facecap/render/outline_distance.hpp"

#include <opencv2/imgproc.hpp>

namespace facecap {

cv::Mat outline_distance(const RasterBuffers& buffers) {
  // The drawn pixels in a frame one pixel wide, so that everything undrawn
  // outside the render connects to the frame's corner.
  cv::Mat inside(buffers.height + 2, buffers.width + 2, CV_8U, cv::Scalar(0));
  for (int y = 0; y < buffers.height; ++y) {
    unsigned char* row = inside.ptr<unsigned char>(y + 1) + 1;
    for (int x = 0; x < buffers.width; ++x) row[x] = buffers.covered(x, y) ? 255 : 0;
  }
  constexpr unsigned char kOutside = 128;
  cv::floodFill(inside, cv::Point(0, 0), cv::Scalar(kOutside), nullptr, cv::Scalar(0), cv::Scalar(0), 4);
  cv::Mat enclosed = inside != kOutside;  // drawn, or undrawn but surrounded
  cv::Mat distance;
  cv::distanceTransform(enclosed, distance, cv::DIST_L2, cv::DIST_MASK_3);
  return distance(cv::Rect(1, 1, buffers.width, buffers.height)).clone();
}

}  // namespace facecap
