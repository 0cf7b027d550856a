#include "facecap/render/shading.hpp"

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// Calls colour_at(i) for every covered pixel i and writes its RGB result to
// the canvas as BGR.
template <typename ColourAt>
void paint_covered_pixels(const RasterBuffers& buffers, cv::Mat& canvas, const ColourAt& colour_at) {
  CV_Assert(canvas.type() == CV_32FC3 && canvas.cols == buffers.width && canvas.rows == buffers.height);
  parallel_for(
      buffers.height,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* row = canvas.ptr<cv::Vec3f>(y);
          for (int x = 0; x < buffers.width; ++x) {
            const size_t i = size_t(y) * buffers.width + x;
            if (buffers.triangle[i] < 0) continue;
            const Vec3f c = colour_at(i);
            row[x] = cv::Vec3f(c.z(), c.y(), c.x());
          }
        }
      },
      16);
}

}  // namespace

void shade_lambertian(const RasterBuffers& buffers, const std::vector<Triangle>& triangles, const Positions& albedo,
                      const Positions& camera_normals, const ShCoeffs& lighting, cv::Mat& canvas) {
  paint_covered_pixels(buffers, canvas, [&](size_t i) -> Vec3f {
    const Vec3f rho = interpolate(buffers, triangles, albedo, i);
    Vec3f n = interpolate(buffers, triangles, camera_normals, i);
    const float len = n.norm();
    if (len > 0) n /= len;
    const Vec3f v = to_viewer_frame(n);
    return rho * sh_shade(lighting, v.x(), v.y(), v.z());
  });
}

void shade_vertex_colors(const RasterBuffers& buffers, const std::vector<Triangle>& triangles, const Positions& colors,
                         cv::Mat& canvas) {
  paint_covered_pixels(buffers, canvas, [&](size_t i) { return interpolate(buffers, triangles, colors, i); });
}

}  // namespace facecap
