#include "facecap/swap/background_warp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/core/parallel.hpp"
#include "facecap/swap/piecewise_affine_map.hpp"

namespace facecap {

cv::Point2f ring_centre(const std::vector<cv::Point2f>& from) {
  cv::Point2f c(0, 0);
  for (const cv::Point2f& p : from) c += p;
  return from.empty() ? c : c * (1.0f / float(from.size()));
}

std::vector<cv::Point2f> fixed_ring(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to,
                                    const cv::Rect& w, float scale) {
  if (from.empty()) return {};
  const cv::Point2f c = ring_centre(from);
  float reach = 0;
  for (const auto* set : {&from, &to})
    for (const cv::Point2f& p : *set) reach = std::max(reach, float(cv::norm(p - c)));
  const float r = scale * reach;
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

namespace {

// Whether a point lies within a pixel of one of `points`.
bool near_any(const std::vector<cv::Point2f>& points, cv::Point2f p) {
  return std::any_of(points.begin(), points.end(), [&](const cv::Point2f& q) { return cv::norm(q - p) < 1.0; });
}

// The thin-plate kernel of squared distance: r^2 log r^2 (twice the usual
// r^2 log r, which the weights absorb).
inline double thin_plate(double r2) { return r2 > 0 ? r2 * std::log(r2) : 0.0; }

// Whether p lies inside the ring: the ring's points go round its centre at
// equal angles, so the side of p's sector's chord decides.
bool inside_ring(const std::vector<cv::Point2f>& ring, cv::Point2f centre, cv::Point2f p) {
  const int n = static_cast<int>(ring.size());
  float angle = std::atan2(p.y - centre.y, p.x - centre.x);
  if (angle < 0) angle += 6.2831853f;
  const int k = std::min(n - 1, static_cast<int>(angle * float(n) / 6.2831853f));
  const cv::Point2f a = ring[k], b = ring[(k + 1) % n];
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) >= 0;
}

}  // namespace

bool BackgroundWarp::fit(const std::vector<cv::Point2f>& points, const std::vector<cv::Point2f>& offsets) {
  // Interpolating thin-plate spline (Bookstein 1989): f(p) = a0 + a1 x + a2 y
  // + sum_i w_i U(|p - p_i|), with K w + P a = offsets and P^T w = 0, in
  // coordinates centred on the ring and scaled to it, for conditioning.
  const int n = static_cast<int>(points.size());
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + 3, n + 3);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + 3, 2);
  for (int i = 0; i < n; ++i) {
    const double xi = (points[i].x - centre_.x) / scale_, yi = (points[i].y - centre_.y) / scale_;
    for (int j = 0; j < i; ++j) {
      const double dx = xi - (points[j].x - centre_.x) / scale_, dy = yi - (points[j].y - centre_.y) / scale_;
      system(i, j) = system(j, i) = thin_plate(dx * dx + dy * dy);
    }
    system(i, n) = system(n, i) = 1;
    system(i, n + 1) = system(n + 1, i) = xi;
    system(i, n + 2) = system(n + 2, i) = yi;
    rhs(i, 0) = offsets[i].x;
    rhs(i, 1) = offsets[i].y;
  }
  const Eigen::MatrixXd solution = system.partialPivLu().solve(rhs);
  if (!solution.allFinite()) return false;
  controls_.resize(n, 4);
  for (int i = 0; i < n; ++i) {
    controls_.row(i) << float((points[i].x - centre_.x) / scale_), float((points[i].y - centre_.y) / scale_),
        float(solution(i, 0)), float(solution(i, 1));
  }
  for (int k = 0; k < 3; ++k) {
    affine_x_[k] = float(solution(n + k, 0));
    affine_y_[k] = float(solution(n + k, 1));
  }
  return true;
}

cv::Point2f BackgroundWarp::offset_at(cv::Point2f p, Eigen::ArrayXf& kernel) const {
  const float x = float((p.x - centre_.x) / scale_), y = float((p.y - centre_.y) / scale_);
  // With Eigen's packet log, the sum over the controls is vectorised.
  kernel = (controls_.col(0).array() - x).square() + (controls_.col(1).array() - y).square();
  kernel *= (kernel + 1e-30f).log();
  return {affine_x_[0] + affine_x_[1] * x + affine_x_[2] * y + (controls_.col(2).array() * kernel).sum(),
          affine_y_[0] + affine_y_[1] * x + affine_y_[2] * y + (controls_.col(3).array() * kernel).sum()};
}

void BackgroundWarp::warp(const cv::Mat& frame, const std::vector<cv::Point2f>& from,
                          const std::vector<cv::Point2f>& to, cv::Rect window, cv::Mat& out,
                          const std::vector<std::vector<cv::Point2f>>& features) {
  window &= cv::Rect(0, 0, frame.cols, frame.rows);
  // The anchors kept: inside the window in both faces (the window's border
  // holds still), and one of two that land within a pixel of each other.
  std::vector<cv::Point2f> src, dst;
  const auto inside = [&](const cv::Point2f& p) {
    return p.x >= window.x && p.y >= window.y && p.x <= window.x + window.width - 1 &&
           p.y <= window.y + window.height - 1;
  };
  for (size_t k = 0; k < std::min(from.size(), to.size()); ++k) {
    if (!inside(from[k]) || !inside(to[k])) continue;
    if (near_any(dst, to[k])) continue;
    src.push_back(from[k]);
    dst.push_back(to[k]);
  }
  controls_.resize(0, 4);
  if (src.empty() || window.empty()) {
    out = frame(window).clone();
    return;
  }
  const std::vector<cv::Point2f> ring = fixed_ring(src, dst, window);
  const std::vector<cv::Point2f> outer = fixed_ring(src, dst, window, kOuterRingScale);
  centre_ = ring_centre(src);
  scale_ = 1.0;
  for (const cv::Point2f& p : outer) scale_ = std::max(scale_, cv::norm(p - centre_));

  // The map from each output pixel back into the frame: its offset is the
  // spline through the anchors' (source minus destination) and the rings'
  // zero inside the outer ring, and zero beyond it.
  std::vector<cv::Point2f> points = dst, offsets(dst.size());
  for (size_t k = 0; k < dst.size(); ++k) offsets[k] = src[k] - dst[k];
  for (const auto* fixed : {&ring, &outer}) {
    for (const cv::Point2f& p : *fixed)
      if (!near_any(points, p)) points.push_back(p);
  }
  offsets.resize(points.size(), cv::Point2f(0, 0));
  // Anchors all in one place leave the rings there too: nothing to fit.
  if (points.size() < 3 || !fit(points, offsets)) {
    controls_.resize(0, 4);
    out = frame(window).clone();
    return;
  }

  // The spline on a grid of nodes `step` pixels apart (each at the centre
  // of its step x step block), then resized to the pixels by bicubic
  // interpolation.
  const int step = std::clamp(window.width / kGridNodesAcross, 1, 8);
  const int nodes_x = (window.width + step - 1) / step, nodes_y = (window.height + step - 1) / step;
  grid_x_.create(nodes_y, nodes_x, CV_32F);
  grid_y_.create(nodes_y, nodes_x, CV_32F);
  parallel_for(
      nodes_y,
      [&](int begin, int end) {
        Eigen::ArrayXf kernel(controls_.rows());
        for (int j = begin; j < end; ++j) {
          float* gx = grid_x_.ptr<float>(j);
          float* gy = grid_y_.ptr<float>(j);
          for (int i = 0; i < nodes_x; ++i) {
            const cv::Point2f p(window.x + step * i + 0.5f * (step - 1), window.y + step * j + 0.5f * (step - 1));
            const cv::Point2f o = inside_ring(outer, centre_, p) ? offset_at(p, kernel) : cv::Point2f(0, 0);
            gx[i] = o.x;
            gy[i] = o.y;
          }
        }
      },
      4);
  const cv::Size fine(nodes_x * step, nodes_y * step);
  const cv::Rect crop(0, 0, window.width, window.height);
  cv::resize(grid_x_, fine_x_, fine, 0, 0, cv::INTER_CUBIC);
  cv::resize(grid_y_, fine_y_, fine, 0, 0, cv::INTER_CUBIC);
  map_x_ = fine_x_(crop);
  map_y_ = fine_y_(crop);
  for (int y = 0; y < window.height; ++y) {
    float* mx = map_x_.ptr<float>(y);
    float* my = map_y_.ptr<float>(y);
    for (int x = 0; x < window.width; ++x) {
      mx[x] += float(window.x + x);
      my[x] += float(window.y + y);
    }
  }
  if (!features.empty()) {
    // The fixed points of the triangles: the inner ring and the window's
    // border, which tile the window with the anchors.
    const std::vector<cv::Point2f> border = window_border(window);
    for (const auto* fixed : {&ring, &border}) {
      src.insert(src.end(), fixed->begin(), fixed->end());
      dst.insert(dst.end(), fixed->begin(), fixed->end());
    }
    keep_triangles_around(features, src, dst, window);
  }
  cv::remap(frame, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
}

void BackgroundWarp::keep_triangles_around(const std::vector<std::vector<cv::Point2f>>& features,
                                           const std::vector<cv::Point2f>& src, const std::vector<cv::Point2f>& dst,
                                           const cv::Rect& window) {
  const int margin = std::max(1, cvRound(kFeatureMargin * window.width));
  const int feather = margin / 2 + 1;
  const cv::Rect whole(0, 0, window.width, window.height);
  std::optional<PiecewiseAffineMap> triangles;
  for (const std::vector<cv::Point2f>& feature : features) {
    std::vector<cv::Point> polygon;
    for (const cv::Point2f& p : feature) {
      if (std::isfinite(p.x) && std::isfinite(p.y))
        polygon.emplace_back(cvRound(p.x) - window.x, cvRound(p.y) - window.y);
    }
    if (polygon.size() < 3) continue;
    // The feature grown by the margin (its outline drawn that thick), and
    // the edge feathered over a third of the margin each way: where the
    // weight is 1 the triangles' map holds, where it is 0 the spline's.
    const cv::Rect bounds = cv::boundingRect(polygon);
    const int reach = margin + feather;
    const cv::Rect region =
        cv::Rect(bounds.x - reach, bounds.y - reach, bounds.width + 2 * reach, bounds.height + 2 * reach) & whole;
    if (region.empty()) continue;
    for (cv::Point& p : polygon) p -= region.tl();
    cv::Mat mask(region.size(), CV_8U, cv::Scalar(0));
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255));
    cv::polylines(mask, std::vector<std::vector<cv::Point>>{polygon}, true, cv::Scalar(255), 2 * margin + 1);
    cv::Mat weight;
    mask.convertTo(weight, CV_32F, 1.0 / 255);
    cv::GaussianBlur(weight, weight, cv::Size(0, 0), std::max(0.5, margin / 3.0));
    if (!triangles) triangles.emplace(src, dst, window);
    // Pixels no triangle covers (none, where the points tile the window)
    // keep the spline's map.
    map_x_(region).copyTo(pa_x_);
    map_y_(region).copyTo(pa_y_);
    triangles->fill(region, pa_x_, pa_y_);
    for (int y = 0; y < region.height; ++y) {
      const float* w = weight.ptr<float>(y);
      const float* ax = pa_x_.ptr<float>(y);
      const float* ay = pa_y_.ptr<float>(y);
      float* mx = map_x_.ptr<float>(region.y + y) + region.x;
      float* my = map_y_.ptr<float>(region.y + y) + region.x;
      for (int x = 0; x < region.width; ++x) {
        mx[x] += w[x] * (ax[x] - mx[x]);
        my[x] += w[x] * (ay[x] - my[x]);
      }
    }
  }
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
