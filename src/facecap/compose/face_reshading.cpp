#include "facecap/compose/face_reshading.hpp"

#include <cmath>

#include "facecap/compose/surface_exposure.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

std::vector<cv::Point2f> project_vertices(const Positions& points, const std::vector<int>& vertices,
                                          const PinholeCamera& camera) {
  std::vector<cv::Point2f> out;
  out.reserve(vertices.size());
  for (int v : vertices) {
    const Vec2f q = camera.project(Vec3f(points.col(v)));
    out.emplace_back(q.x(), q.y());
  }
  return out;
}

cv::Rect projected_bounds(const Positions& points, const PinholeCamera& camera) {
  float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
  for (Eigen::Index v = 0; v < points.cols(); ++v) {
    const Vec3f p = points.col(v);
    if (!(p.z() > 0)) continue;
    const Vec2f q = camera.project(p);
    x0 = std::min(x0, q.x()), y0 = std::min(y0, q.y());
    x1 = std::max(x1, q.x()), y1 = std::max(y1, q.y());
  }
  if (x1 < x0) return {};
  // Clamp before converting: a point near the camera plane projects far away.
  auto c = [](float v) { return static_cast<int>(std::clamp(v, -1e6f, 1e6f)); };
  return cv::Rect(cv::Point(c(std::floor(x0)), c(std::floor(y0))),
                  cv::Point(c(std::ceil(x1)) + 1, c(std::ceil(y1)) + 1));
}

float shading_ratio(float s_old, float s_new, float facing) {
  const float ratio = s_old > 0.05f ? std::clamp(s_new / s_old, 0.5f, 2.0f) : 1.0f;
  const float trust = smoothstep(kGrazingFacing, kFacing, facing);
  return trust < 1 ? std::pow(ratio, trust) : ratio;
}

FaceLayer reshade_face(const cv::Mat& source, const Positions& old_points, const Positions& new_points,
                       const std::vector<Triangle>& triangles, const ShCoeffs& lighting, const PinholeCamera& camera,
                       int margin) {
  const cv::Rect face = projected_bounds(new_points, camera);
  FaceLayer layer = make_layer(source, face, margin);
  if (layer.box.area() == 0) return layer;
  // Rasterise into the window: the same camera with its principal point shifted.
  const PinholeCamera window = camera.cropped(layer.box.x, layer.box.y);
  RasterBuffers buffers;
  buffers.resize(layer.box.width, layer.box.height);
  rasterize(new_points, triangles, window, buffers);
  const Positions old_normals = vertex_normals(old_points, triangles);
  const Positions new_normals = vertex_normals(new_points, triangles);
  // Where the frame saw the new surface edge-on or not at all (surface_exposure.hpp).
  const std::vector<float> exposure = vertex_exposure(old_points, new_points, triangles, camera);
  cv::Mat trust(layer.box.size(), CV_32F, cv::Scalar(1.0f));
  parallel_for(
      layer.box.height,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* out = layer.colour.ptr<cv::Vec3b>(y);
          auto* mask = layer.mask.ptr<uchar>(y);
          for (int x = 0; x < layer.box.width; ++x) {
            const size_t i = size_t(y) * layer.box.width + x;
            if (buffers.triangle[i] < 0) continue;
            // The same surface point on the old surface, in the source frame.
            const Vec3f old_point = interpolate(buffers, triangles, old_points, i);
            const Vec2f q = camera.project(old_point);
            const Vec3f rgb = sample_bilinear_rgb8(source, q.x(), q.y());
            const Vec3f n_old = interpolate(buffers, triangles, old_normals, i).normalized();
            const Vec3f n_new = interpolate(buffers, triangles, new_normals, i).normalized();
            const Vec3f vo = to_viewer_frame(n_old), vn = to_viewer_frame(n_new);
            const float s_old = sh_shade(lighting, vo.x(), vo.y(), vo.z());
            const float s_new = sh_shade(lighting, vn.x(), vn.y(), vn.z());
            const float ratio = shading_ratio(s_old, s_new, std::min(vo.z(), vn.z()));
            out[x] = cv::Vec3b(cv::saturate_cast<uchar>(rgb.z() * ratio * 255),
                               cv::saturate_cast<uchar>(rgb.y() * ratio * 255),
                               cv::saturate_cast<uchar>(rgb.x() * ratio * 255));
            mask[x] = 255;
            const Triangle& t = triangles[buffers.triangle[i]];
            const Vec2f w = buffers.bary[i];
            trust.ptr<float>(y)[x] = exposure_trust((1.0f - w.x() - w.y()) * exposure[t[0]] + w.x() * exposure[t[1]] +
                                                    w.y() * exposure[t[2]]);
          }
        }
      },
      16);
  // What the frame did not show, from the skin around it (not the eyes or
  // the background, which the layer holds beyond the mask): a Gaussian of a
  // fortieth of the face's width (7 px at 720p), about the width of a lid.
  fill_untrusted(layer.colour, trust, layer.mask, 0.025 * face.width);
  return layer;
}

}  // namespace facecap
