#include "facecap/render/uv_pass.hpp"

#include <algorithm>
#include <cmath>

namespace facecap {

namespace {

uint16_t unit_to_16(float v) { return uint16_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f)); }

}  // namespace

cv::Mat uv_pass(const TriangleMesh& mesh, const Positions& camera_points, const PinholeCamera& camera, cv::Size size,
                RasterBuffers& buffers) {
  if (buffers.width != size.width || buffers.height != size.height) buffers.resize(size.width, size.height);
  rasterize(camera_points, mesh.triangles, camera, buffers);
  cv::Mat pass(size, CV_16UC4, cv::Scalar::all(0));
  for (int y = buffers.drawn_y0; y < buffers.drawn_y1; ++y) {
    auto* out = pass.ptr<cv::Vec<uint16_t, 4>>(y);
    for (int x = buffers.drawn_x0; x < buffers.drawn_x1; ++x) {
      const size_t i = size_t(y) * size.width + x;
      const int t = buffers.triangle[i];
      if (t < 0) continue;
      const Vec2f uv = uv_at(mesh, t, buffers.bary[i]);
      out[x] = {0, unit_to_16(uv.y()), unit_to_16(uv.x()), 65535};
    }
  }
  return pass;
}

}  // namespace facecap
