#include "facecap/swap/piecewise_affine_map.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// Delaunay triangles of `points` (indices into them).
std::vector<cv::Vec3i> delaunay(const std::vector<cv::Point2f>& points, const cv::Rect& window) {
  cv::Subdiv2D subdiv(cv::Rect(window.x - 2, window.y - 2, window.width + 4, window.height + 4));
  std::vector<int> id_of;  // Subdiv2D vertex id -> our point index
  for (size_t i = 0; i < points.size(); ++i) {
    const int id = subdiv.insert(points[i]);
    if (id >= static_cast<int>(id_of.size())) id_of.resize(id + 1, -1);
    id_of[id] = static_cast<int>(i);  // a duplicate point maps to its last index
  }
  std::vector<cv::Vec6f> list;
  subdiv.getTriangleList(list);
  std::vector<cv::Vec3i> triangles;
  for (const cv::Vec6f& t : list) {
    cv::Vec3i tri;
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      int edge = 0, vertex = 0;
      const int r = subdiv.locate(cv::Point2f(t[2 * k], t[2 * k + 1]), edge, vertex);
      ok = r == cv::Subdiv2D::PTLOC_VERTEX && vertex < static_cast<int>(id_of.size()) && id_of[vertex] >= 0;
      if (ok) tri[k] = id_of[vertex];
    }
    if (ok) triangles.push_back(tri);
  }
  return triangles;
}

}  // namespace

std::vector<cv::Point2f> window_border(const cv::Rect& w) {
  const float x0 = w.x, y0 = w.y, x1 = w.x + w.width - 1, y1 = w.y + w.height - 1;
  const float xm = 0.5f * (x0 + x1), ym = 0.5f * (y0 + y1);
  return {{x0, y0}, {xm, y0}, {x1, y0}, {x1, ym}, {x1, y1}, {xm, y1}, {x0, y1}, {x0, ym}};
}

PiecewiseAffineMap::PiecewiseAffineMap(std::vector<cv::Point2f> src, std::vector<cv::Point2f> dst,
                                       const cv::Rect& window)
    : src_(std::move(src)), dst_(std::move(dst)), window_(window), triangles_(delaunay(dst_, window)) {}

void PiecewiseAffineMap::fill(const cv::Rect& region, cv::Mat& map_x, cv::Mat& map_y) const {
  const cv::Rect& window = window_;
  const std::vector<cv::Point2f>&src = src_, &dst = dst_;
  // Each destination triangle samples its source triangle (a later one
  // overwriting an earlier one on their shared edge), on the pool in bands
  // of rows, each band visiting the triangles in their order: the map does
  // not depend on the thread count.
  const int rx0 = window.x + region.x, rx1 = window.x + region.x + region.width - 1;
  parallel_for(
      region.height,
      [&](int band_begin, int band_end) {
        const int band_y0 = window.y + region.y + band_begin, band_y1 = window.y + region.y + band_end - 1;
        for (const cv::Vec3i& t : triangles_) {
          const cv::Point2f d[3] = {dst[t[0]], dst[t[1]], dst[t[2]]};
          const cv::Point2f s[3] = {src[t[0]], src[t[1]], src[t[2]]};
          const float area = (d[1].x - d[0].x) * (d[2].y - d[0].y) - (d[1].y - d[0].y) * (d[2].x - d[0].x);
          if (std::abs(area) < 1e-3f) continue;
          const int x0 = std::max(rx0, int(std::floor(std::min({d[0].x, d[1].x, d[2].x}))));
          const int x1 = std::min(rx1, int(std::ceil(std::max({d[0].x, d[1].x, d[2].x}))));
          const int y0 = std::max(band_y0, int(std::floor(std::min({d[0].y, d[1].y, d[2].y}))));
          const int y1 = std::min(band_y1, int(std::ceil(std::max({d[0].y, d[1].y, d[2].y}))));
          for (int y = y0; y <= y1; ++y) {
            float* mx = map_x.ptr<float>(y - window.y - region.y) - window.x - region.x;
            float* my = map_y.ptr<float>(y - window.y - region.y) - window.x - region.x;
            for (int x = x0; x <= x1; ++x) {
              const float w0 = ((d[1].x - x) * (d[2].y - y) - (d[1].y - y) * (d[2].x - x)) / area;
              const float w1 = ((d[2].x - x) * (d[0].y - y) - (d[2].y - y) * (d[0].x - x)) / area;
              const float w2 = 1.0f - w0 - w1;
              if (w0 < -1e-4f || w1 < -1e-4f || w2 < -1e-4f) continue;
              mx[x] = w0 * s[0].x + w1 * s[1].x + w2 * s[2].x;
              my[x] = w0 * s[0].y + w1 * s[1].y + w2 * s[2].y;
            }
          }
        }
      },
      32);
}

}  // namespace facecap
