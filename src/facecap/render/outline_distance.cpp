#include "facecap/render/outline_distance.hpp"

#include <algorithm>
#include <iterator>
#include <opencv2/imgproc.hpp>

namespace facecap {

cv::Mat outline_distance(const RasterBuffers& buffers) {
  cv::Mat out(buffers.height, buffers.width, CV_32F, cv::Scalar(0));
  // The box that holds the drawn pixels. Around it every pixel is undrawn
  // and connects to the border, so a frame one pixel wide around the box
  // stands for all of them: a path from inside to any pixel beyond the
  // frame crosses it, and the distances inside the box are those over the
  // whole buffers (a swap's window is some twice the face's box: half the
  // work).
  int x0 = buffers.width, x1 = 0, y0 = buffers.height, y1 = 0;
  for (int y = 0; y < buffers.height; ++y) {
    const int* row = buffers.triangle.data() + size_t(y) * buffers.width;
    const int* first = std::find_if(row, row + buffers.width, [](int t) { return t >= 0; });
    if (first == row + buffers.width) continue;
    const int* last =
        std::find_if(std::make_reverse_iterator(row + buffers.width), std::make_reverse_iterator(first), [](int t) {
          return t >= 0;
        }).base();
    x0 = std::min(x0, int(first - row));
    x1 = std::max(x1, int(last - row));
    y0 = std::min(y0, y);
    y1 = y + 1;
  }
  if (x0 >= x1 || y0 >= y1) return out;
  // The drawn pixels in that frame, so that everything undrawn outside the
  // render connects to the frame's corner.
  cv::Mat inside(y1 - y0 + 2, x1 - x0 + 2, CV_8U, cv::Scalar(0));
  for (int y = y0; y < y1; ++y) {
    unsigned char* row = inside.ptr<unsigned char>(y - y0 + 1) + 1;
    for (int x = x0; x < x1; ++x) row[x - x0] = buffers.covered(x, y) ? 255 : 0;
  }
  constexpr unsigned char kOutside = 128;
  cv::floodFill(inside, cv::Point(0, 0), cv::Scalar(kOutside), nullptr, cv::Scalar(0), cv::Scalar(0), 4);
  cv::Mat enclosed = inside != kOutside;  // drawn, or undrawn but surrounded
  cv::Mat distance;
  cv::distanceTransform(enclosed, distance, cv::DIST_L2, cv::DIST_MASK_3);
  distance(cv::Rect(1, 1, x1 - x0, y1 - y0)).copyTo(out(cv::Rect(x0, y0, x1 - x0, y1 - y0)));
  return out;
}

}  // namespace facecap
