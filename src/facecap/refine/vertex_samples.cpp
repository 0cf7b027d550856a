#include "facecap/refine/vertex_samples.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "facecap/core/image_sampling.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

VertexSamples sample_vertices(const cv::Mat& image, const Positions& p, const Positions& n,
                              const std::vector<Triangle>& triangles, const PinholeCamera& camera) {
  RasterBuffers buffers;
  return sample_vertices(image, p, n, triangles, camera, buffers);
}

VertexSamples sample_vertices(const cv::Mat& image, const Positions& p, const Positions& n,
                              const std::vector<Triangle>& triangles, const PinholeCamera& camera,
                              RasterBuffers& buffers) {
  return sample_vertices(image, p, n, p, triangles, camera, buffers);
}

VertexSamples sample_vertices(const cv::Mat& image, const Positions& p, const Positions& n,
                              const Positions& occluder_points, const std::vector<Triangle>& occluder_triangles,
                              const PinholeCamera& camera, RasterBuffers& buffers) {
  if (buffers.width != image.cols || buffers.height != image.rows) buffers.resize(image.cols, image.rows);
  rasterize(occluder_points, occluder_triangles, camera, buffers);
  VertexSamples s;
  s.visible = vertex_visibility(p, n, camera, buffers, 0.1f);
  s.colour = Positions::Zero(3, p.cols());
  for (Eigen::Index i = 0; i < p.cols(); ++i) {
    if (!s.visible[i]) continue;
    const Vec2f q = camera.project(Vec3f(p.col(i)));
    s.colour.col(i) = sample_bilinear_rgb8(image, q.x(), q.y());
    ++s.visible_count;
  }
  return s;
}

void erode_observations(VertexSamples& s, const VertexAdjacency& adjacency, int rings,
                        const std::vector<bool>& open_boundary) {
  for (int r = 0; r < rings; ++r) {
    std::vector<bool> next = s.visible;
    for (size_t i = 0; i < s.visible.size(); ++i) {
      if (!s.visible[i]) continue;
      if (r == 0 && !open_boundary.empty() && open_boundary[i]) next[i] = false;  // one ring from the hole
      for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1] && next[i]; ++k)
        next[i] = s.visible[adjacency.indices[k]];
    }
    s.visible = std::move(next);
  }
  s.visible_count = static_cast<int>(std::count(s.visible.begin(), s.visible.end(), true));
}

void drop_oblique_observations(VertexSamples& s, const Positions& p, const Positions& n, float min_facing) {
  for (size_t i = 0; i < s.visible.size(); ++i) {
    if (!s.visible[i]) continue;
    if (view_facing(p.col(i), n.col(i)) < min_facing) {
      s.visible[i] = false;
      --s.visible_count;
    }
  }
}

std::vector<cv::Mat> image_pyramid(const cv::Mat& bgr8, int levels) {
  std::vector<cv::Mat> out(std::max(1, levels));
  out[0] = bgr8;
  for (int l = 1; l < levels; ++l) {
    cv::resize(out[l - 1], out[l], cv::Size((out[l - 1].cols + 1) / 2, (out[l - 1].rows + 1) / 2), 0, 0,
               cv::INTER_AREA);
  }
  return out;
}

PinholeCamera scaled_camera(const PinholeCamera& c, double factor) {
  // Pixel x at full resolution covers [x - 0.5, x + 0.5]; at 1/factor it is
  // (x + 0.5) / factor - 0.5.
  return {c.focal / factor, (c.cx + 0.5) / factor - 0.5, (c.cy + 0.5) / factor - 0.5};
}

}  // namespace facecap
