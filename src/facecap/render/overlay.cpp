#include "facecap/render/overlay.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace facecap {

void draw_landmarks(cv::Mat& image, const Landmarks& landmarks, const cv::Scalar& colour, int radius) {
  for (const Vec2f& p : landmarks) cv::circle(image, cv::Point2f(p.x(), p.y()), radius, colour, -1, cv::LINE_AA);
}

void draw_wireframe(cv::Mat& image, const Positions& camera_points, const std::vector<Polygon>& polygons,
                    const PinholeCamera& camera, const cv::Scalar& colour) {
  std::vector<cv::Point2f> projected(camera_points.cols());
  for (Eigen::Index i = 0; i < camera_points.cols(); ++i) {
    const Vec2f q = camera.project(Vec3f(camera_points.col(i)));
    projected[i] = cv::Point2f(q.x(), q.y());
  }
  cv::Mat layer = image.clone();
  for (const Polygon& poly : polygons) {
    const Vec3f a = camera_points.col(poly.v[0]), b = camera_points.col(poly.v[1]), c = camera_points.col(poly.v[2]);
    if ((b - a).cross(c - a).dot(a) >= 0.0f) continue;  // faces away
    const int n = poly.size();
    for (int k = 0; k < n; ++k)
      cv::line(layer, projected[poly.v[k]], projected[poly.v[(k + 1) % n]], colour, 1, cv::LINE_AA);
  }
  cv::addWeighted(layer, 0.45, image, 0.55, 0.0, image);
}

void draw_gaze(cv::Mat& image, const Vec2d& iris_px, double iris_radius_px, const Vec3d& iris_camera,
               const Vec3d& direction, double length_cm, const PinholeCamera& camera, const cv::Scalar& colour) {
  constexpr int kShift = 4;  // sub-pixel drawing
  auto fixed = [](const Vec2d& p) {
    return cv::Point(int(std::lround(p.x() * (1 << kShift))), int(std::lround(p.y() * (1 << kShift))));
  };
  cv::circle(image, fixed(iris_px), int(std::lround(iris_radius_px * (1 << kShift))), colour, 1, cv::LINE_AA, kShift);
  const Vec3d tip = iris_camera + length_cm * direction.normalized();
  if (!(tip.z() > 0.1)) return;
  cv::arrowedLine(image, fixed(camera.project(iris_camera)), fixed(camera.project(tip)), colour, 2, cv::LINE_AA, kShift,
                  0.2);
}

void draw_caption(cv::Mat& image, const std::string& text) {
  int baseline = 0;
  const double scale = std::max(0.4, image.cols / 1600.0);
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  cv::rectangle(image, cv::Rect(0, 0, size.width + 12, size.height + baseline + 10), cv::Scalar(0, 0, 0), -1);
  cv::putText(image, text, cv::Point(6, size.height + 5), cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

}  // namespace facecap
