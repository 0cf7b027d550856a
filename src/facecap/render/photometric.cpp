#include "facecap/render/photometric.hpp"

#include <opencv2/imgproc.hpp>

#include "facecap/render/shading.hpp"

namespace facecap {

cv::Mat interpolate_attribute(const RasterBuffers& b, const std::vector<Triangle>& triangles, const Positions& attr) {
  cv::Mat out(b.height, b.width, CV_32FC3, cv::Scalar::all(0));
  for (int y = 0; y < b.height; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < b.width; ++x) {
      const size_t i = size_t(y) * b.width + x;
      if (b.triangle[i] < 0) continue;
      const Vec3f v = interpolate(b, triangles, attr, i);
      row[x] = cv::Vec3f(v.x(), v.y(), v.z());
    }
  }
  return out;
}

cv::Mat face_normal_image(const RasterBuffers& b, const std::vector<Triangle>& triangles, const Positions& p) {
  std::vector<Vec3f> normals(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Vec3f a = p.col(triangles[t][0]), bb = p.col(triangles[t][1]), c = p.col(triangles[t][2]);
    normals[t] = (bb - a).cross(c - a).normalized();
  }
  cv::Mat out(b.height, b.width, CV_32FC3, cv::Scalar::all(0));
  for (int y = 0; y < b.height; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < b.width; ++x) {
      const int t = b.triangle[size_t(y) * b.width + x];
      if (t >= 0) row[x] = cv::Vec3f(normals[t].x(), normals[t].y(), normals[t].z());
    }
  }
  return out;
}

PhotometricError photometric_error(const cv::Mat& frame, const Positions& points,
                                   const std::vector<Triangle>& triangles, const Positions& normals,
                                   const Positions& albedo, const ShCoeffs& lighting, const PinholeCamera& camera,
                                   bool heat_map) {
  RasterBuffers buffers;
  buffers.resize(frame.cols, frame.rows);
  rasterize(points, triangles, camera, buffers);
  cv::Mat rendered(frame.rows, frame.cols, CV_32FC3, cv::Scalar::all(0));
  shade_lambertian(buffers, triangles, albedo, normals, lighting, rendered);
  PhotometricError out;
  double sum = 0;
  cv::Mat error_map;
  if (heat_map) error_map = cv::Mat(frame.rows, frame.cols, CV_8U, cv::Scalar(0));
  for (int y = 0; y < frame.rows; ++y) {
    const auto* f = frame.ptr<cv::Vec3b>(y);
    const auto* r = rendered.ptr<cv::Vec3f>(y);
    for (int x = 0; x < frame.cols; ++x) {
      if (!buffers.covered(x, y)) continue;
      double e = 0;
      for (int c = 0; c < 3; ++c) e += std::abs(double(f[x][c]) - std::clamp(double(r[x][c]) * 255.0, 0.0, 255.0));
      e /= 3.0;
      sum += e;
      ++out.pixels;
      if (heat_map)
        error_map.at<uchar>(y, x) = static_cast<uchar>(std::min(255.0, e * 255.0 / 40.0));  // 40 levels = red
    }
  }
  out.mean_abs = out.pixels > 0 ? sum / out.pixels : 0.0;
  if (heat_map) {
    cv::Mat coloured;
    cv::applyColorMap(error_map, coloured, cv::COLORMAP_JET);
    cv::Mat base = frame * 0.4;
    coloured.copyTo(base, error_map > 0);
    out.heat_map = base;
  }
  return out;
}

}  // namespace facecap
