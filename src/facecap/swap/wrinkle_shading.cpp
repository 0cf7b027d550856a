#include "facecap/swap/wrinkle_shading.hpp"

#include <algorithm>
#include <chrono>

#include "facecap/core/parallel.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/refine/refiner.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

WrinkleShading::WrinkleShading(const TriangleMesh& skin, Eigen::VectorXf source_expression)
    : skin_vertices_(skin.num_vertices, false), source_expression_(std::move(source_expression)) {
  for (const Triangle& tri : skin.triangles)
    for (const int v : tri) skin_vertices_[v] = true;
}

double WrinkleShading::shade(const MeshHierarchy& hierarchy, const Positions& fine,
                             const Eigen::VectorXf& target_expression, const ShCoeffs& lighting,
                             const Positions& target_points, const Positions& swapped_points,
                             const PinholeCamera& window, cv::Mat& render) {
  const int finest = hierarchy.num_levels() - 1;
  const MeshLevel& level = hierarchy.level(finest);
  if (fine.cols() != level.num_vertices) return 0.0;
  double setup_ms = 0;
  if (!coating_) {
    const auto setup_start = std::chrono::steady_clock::now();
    coating_ = std::make_unique<CoatingTransfer>(level.triangles, level.num_vertices);
    reference_.emplace(source_expression_);
    fine_skin_ = masked_triangles(level.triangles, hierarchy.prolong_mask(skin_vertices_, finest));
    setup_ms = ms_since(setup_start);
  }
  const Positions base_target = hierarchy.prolong_from_coarse(target_points, finest);
  const Positions base_swapped = hierarchy.prolong_from_coarse(swapped_points, finest);
  const Positions xi = coating_->coating(fine, base_target);
  if (reference_->offer(target_expression)) reference_coating_ = xi;
  const Positions swapped_normals = level_normals(level, base_swapped);
  const Positions motion =
      rotate_between_normals(xi - reference_coating_, level_normals(level, base_target), swapped_normals);
  const Positions wrinkled = coating_->solve(base_swapped, motion);
  const Positions wrinkled_normals = level_normals(level, wrinkled);
  RasterBuffers buffers;
  buffers.resize(render.cols, render.rows);
  rasterize(wrinkled, fine_skin_, window, buffers);
  parallel_for(
      render.rows,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* colour = render.ptr<cv::Vec3f>(y);
          for (int x = 0; x < render.cols; ++x) {
            const size_t i = size_t(y) * render.cols + x;
            if (buffers.triangle[i] < 0) continue;
            const Vec3f nw = to_viewer_frame(interpolate(buffers, fine_skin_, wrinkled_normals, i).normalized());
            const Vec3f nc = to_viewer_frame(interpolate(buffers, fine_skin_, swapped_normals, i).normalized());
            const float sc = sh_shade(lighting, nc.x(), nc.y(), nc.z());
            if (!(sc > 0.05f)) continue;
            const float ratio = std::clamp(sh_shade(lighting, nw.x(), nw.y(), nw.z()) / sc, 0.5f, 2.0f);
            colour[x] *= ratio;
          }
        }
      },
      16);
  return setup_ms;
}

}  // namespace facecap
