#include "facecap/swap/background_warp.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/core/parallel.hpp"

namespace facecap {

std::vector<cv::Point2f> window_border(const cv::Rect& w) {
  const float x0 = w.x, y0 = w.y, x1 = w.x + w.width - 1, y1 = w.y + w.height - 1;
  const float xm = 0.5f * (x0 + x1), ym = 0.5f * (y0 + y1);
  return {{x0, y0}, {xm, y0}, {x1, y0}, {x1, ym}, {x1, y1}, {xm, y1}, {x0, y1}, {x0, ym}};
}

std::vector<cv::Point2f> fixed_ring(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                                    const cv::Rect& w) {
  if (from.empty()) return {};
  cv::Point2f c(0, 0);
  for (const cv::Point2f& p : from) c += p;
  c *= 1.0f / float(from.size());
  float reach = 0;
  for (const auto* set : {&from, &to})
    for (const cv::Point2f& p : *set) reach = std::max(reach, float(cv::norm(p - c)));
  const float r = kRingScale * reach;
  const float x0 = w.x + 2.0f, y0 = w.y + 2.0f, x1 = w.x + w.width - 3.0f, y1 = w.y + w.height - 3.0f;
  std::vector<cv::Point2f> ring;
  for (int k = 0; k < kRingPoints; ++k) {
    const float angle = 6.2831853f * float(k) / kRingPoints;
    const cv::Point2f dir(std::cos(angle), std::sin(angle));
    // The largest t <= r with c + t dir inside [x0, x1] x [y0, y1].
    float t = r;
    if (dir.x > 1e-6f) t = std::min(t, (x1 - c.x) / dir.x);
    if (dir.x < -1e-6f) t = std::min(t, (x0 - c.x) / dir.x);
    if (dir.y > 1e-6f) t = std::min(t, (y1 - c.y) / dir.y);
    if (dir.y < -1e-6f) t = std::min(t, (y0 - c.y) / dir.y);
    ring.push_back(c + std::max(0.0f, t) * dir);
  }
  return ring;
}

void BackgroundWarp::triangulate(const std::vector<cv::Point2f>& points, const cv::Rect& window) {
  cv::Subdiv2D subdiv(cv::Rect(window.x - 2, window.y - 2, window.width + 4, window.height + 4));
  std::vector<int> id_of;  // Subdiv2D vertex id -> our point index
  for (size_t i = 0; i < points.size(); ++i) {
    const int id = subdiv.insert(points[i]);
    if (id >= static_cast<int>(id_of.size())) id_of.resize(id + 1, -1);
    id_of[id] = static_cast<int>(i);  // a duplicate point maps to its last index
  }
  std::vector<cv::Vec6f> list;
  subdiv.getTriangleList(list);
  triangles_.clear();
  for (const cv::Vec6f& t : list) {
    cv::Vec3i tri;
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      int edge = 0, vertex = 0;
      const int r = subdiv.locate(cv::Point2f(t[2 * k], t[2 * k + 1]), edge, vertex);
      ok = r == cv::Subdiv2D::PTLOC_VERTEX && vertex < static_cast<int>(id_of.size()) && id_of[vertex] >= 0;
      if (ok) tri[k] = id_of[vertex];
    }
    if (ok) triangles_.push_back(tri);
  }
}

void BackgroundWarp::warp(const cv::Mat& frame, const std::vector<cv::Point2f>& from,
                          const std::vector<cv::Point2f>& to, cv::Rect window, cv::Mat& out) {
  window &= cv::Rect(0, 0, frame.cols, frame.rows);
  // Anchors, then the fixed ring (the same points in both sets), then the
  // border. An anchor outside the window in either face (one cut off by the
  // frame's edge) is left out, since the border holds still: all the
  // destination points lie in the window, and their triangles tile it.
  std::vector<cv::Point2f> src, dst;
  const auto inside = [&](const cv::Point2f& p) {
    return p.x >= window.x && p.y >= window.y && p.x <= window.x + window.width - 1 &&
           p.y <= window.y + window.height - 1;
  };
  for (size_t k = 0; k < std::min(from.size(), to.size()); ++k) {
    if (!inside(from[k]) || !inside(to[k])) continue;
    src.push_back(from[k]);
    dst.push_back(to[k]);
  }
  const auto ring = fixed_ring(src, dst, window);
  const auto border = window_border(window);
  for (const auto* fixed : {&ring, &border}) {
    src.insert(src.end(), fixed->begin(), fixed->end());
    dst.insert(dst.end(), fixed->begin(), fixed->end());
  }
  triangulate(dst, window);
  // Identity map, then each destination triangle samples its source
  // triangle (a later triangle overwriting an earlier one on their shared
  // edge). On the pool in bands of rows, each band visiting the triangles in
  // their order, so the map does not depend on the thread count.
  map_x_.create(window.size(), CV_32F);
  map_y_.create(window.size(), CV_32F);
  parallel_for(
      window.height,
      [&](int band_begin, int band_end) {
        for (int y = band_begin; y < band_end; ++y) {
          float* mx = map_x_.ptr<float>(y);
          float* my = map_y_.ptr<float>(y);
          for (int x = 0; x < window.width; ++x) {
            mx[x] = float(window.x + x);
            my[x] = float(window.y + y);
          }
        }
        for (const cv::Vec3i& t : triangles_) {
          const cv::Point2f d[3] = {dst[t[0]], dst[t[1]], dst[t[2]]};
          const cv::Point2f s[3] = {src[t[0]], src[t[1]], src[t[2]]};
          const float area = (d[1].x - d[0].x) * (d[2].y - d[0].y) - (d[1].y - d[0].y) * (d[2].x - d[0].x);
          if (std::abs(area) < 1e-3f) continue;
          const int x0 = std::max(window.x, int(std::floor(std::min({d[0].x, d[1].x, d[2].x}))));
          const int x1 = std::min(window.x + window.width - 1, int(std::ceil(std::max({d[0].x, d[1].x, d[2].x}))));
          const int y0 = std::max(window.y + band_begin, int(std::floor(std::min({d[0].y, d[1].y, d[2].y}))));
          const int y1 = std::min(window.y + band_end - 1, int(std::ceil(std::max({d[0].y, d[1].y, d[2].y}))));
          for (int y = y0; y <= y1; ++y) {
            float* mx = map_x_.ptr<float>(y - window.y);
            float* my = map_y_.ptr<float>(y - window.y);
            for (int x = x0; x <= x1; ++x) {
              const float w0 = ((d[1].x - x) * (d[2].y - y) - (d[1].y - y) * (d[2].x - x)) / area;
              const float w1 = ((d[2].x - x) * (d[0].y - y) - (d[2].y - y) * (d[0].x - x)) / area;
              const float w2 = 1.0f - w0 - w1;
              if (w0 < -1e-4f || w1 < -1e-4f || w2 < -1e-4f) continue;
              mx[x - window.x] = w0 * s[0].x + w1 * s[1].x + w2 * s[2].x;
              my[x - window.x] = w0 * s[0].y + w1 * s[1].y + w2 * s[2].y;
            }
          }
        }
      },
      32);
  cv::remap(frame, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
}

std::vector<bool> anchors_facing(const std::vector<int>& anchors, const Positions& target_points,
                                 const Positions& target_normals, const Positions& swapped_points,
                                 const Positions& swapped_normals, int skin_vertices) {
  const auto faces_camera = [](const Positions& points, const Positions& normals, int v) {
    return normals.col(v).dot(points.col(v)) < 0;  // the camera sits at the origin
  };
  std::vector<bool> shown(anchors.size(), true);
  for (size_t k = 0; k < anchors.size(); ++k) {
    const int v = anchors[k];
    if (v < skin_vertices)
      shown[k] = faces_camera(target_points, target_normals, v) && faces_camera(swapped_points, swapped_normals, v);
  }
  return shown;
}

}  // namespace facecap
