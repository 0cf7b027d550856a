#include "facecap/render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "facecap/core/parallel.hpp"

namespace facecap {

void RasterBuffers::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  depth.assign(n, std::numeric_limits<float>::infinity());
  triangle.assign(n, -1);
  bary.assign(n, Vec2f::Zero());
  drawn_x0 = drawn_x1 = drawn_y0 = drawn_y1 = 0;
}

namespace {

// tan of the steepest view angle the depth test allows for (76 degrees):
// grazing vertices beyond it get no extra slack.
constexpr float kMaxVisibilitySlope = 4.0f;

// The edge function (a - p) x (b - p) of the edge a -> b, evaluated with the
// endpoints in a canonical order u, v and the sign restored: with E = v - u,
// it is E.x (p.y - u.y) - E.y (p.x - u.x), the sign folded into E (negation
// is exact, and round-to-nearest rounds -x as it rounds x). Two triangles
// sharing an edge then get exactly opposite values at every pixel (they run
// the same instructions on the same u and E), so a pixel on the edge is
// inside at least one of them: no cracks. The differences to u come first,
// so the values keep the precision of a small triangle's own coordinates.
class CanonicalEdge {
 public:
  CanonicalEdge(const Vec2f& a, const Vec2f& b) {
    const bool flip = b.x() < a.x() || (b.x() == a.x() && b.y() < a.y());
    const Vec2f& u = flip ? b : a;
    const Vec2f& v = flip ? a : b;
    const float sign = flip ? -1.0f : 1.0f;
    ux_ = u.x();
    uy_ = u.y();
    ex_ = sign * (v.x() - u.x());
    ey_ = sign * (v.y() - u.y());
  }
  // The part of the value that is constant along row py.
  float row(float py) const { return ex_ * (py - uy_); }
  // The value at (px, py), given row(py).
  float at(float row_value, float px) const { return row_value - ey_ * (px - ux_); }

 private:
  float ux_, uy_, ex_, ey_;
};

struct ProjectedTriangle {
  Vec2f p[3];
  float inv_z[3];
  int index;
  float min_x, max_x, min_y, max_y;  // the screen-space bounds
};

// A call's working arrays, kept by each calling thread from call to call: a
// finest level's setup alone is 4 MB, which a fresh vector zeroed (and the
// allocator took from the kernel) every frame. The caller of parallel_for
// runs only its own job's chunks, so no other call reaches them meanwhile.
struct RasterScratch {
  std::vector<Vec2f> screen;
  std::vector<float> inv_z;
  std::vector<ProjectedTriangle> setup;
  std::vector<char> kept;
};

RasterScratch& scratch() {
  thread_local RasterScratch s;
  return s;
}

}  // namespace

void rasterize(const Positions& camera_points, const std::vector<Triangle>& triangles, const PinholeCamera& camera,
               RasterBuffers& out, const RasterOptions& options) {
  const int width = out.width;
  const int height = out.height;
  if (width <= 0 || height <= 0) return;

  // Project every vertex once (a vertex is a corner of about six triangles).
  const int num_points = static_cast<int>(camera_points.cols());
  RasterScratch& work = scratch();
  std::vector<Vec2f>& screen = work.screen;
  std::vector<float>& inv_z = work.inv_z;
  screen.resize(num_points);
  inv_z.resize(num_points);
  parallel_for(
      num_points,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          const Vec3f p = camera_points.col(i);
          screen[i] = camera.project(p);
          inv_z[i] = 1.0f / p.z();
        }
      },
      4096);

  // Set up and cull each triangle.
  const int num_triangles = static_cast<int>(triangles.size());
  std::vector<ProjectedTriangle>& setup = work.setup;
  std::vector<char>& kept = work.kept;
  setup.resize(num_triangles);
  kept.resize(num_triangles);
  parallel_for(
      num_triangles,
      [&](int b, int e) {
        for (int t = b; t < e; ++t) {
          kept[t] = 0;
          const Triangle& tri = triangles[t];
          const Vec3f a = camera_points.col(tri[0]);
          const Vec3f bv = camera_points.col(tri[1]);
          const Vec3f c = camera_points.col(tri[2]);
          if (a.z() < options.near_z || bv.z() < options.near_z || c.z() < options.near_z) continue;
          if (options.cull_back_faces && (bv - a).cross(c - a).dot(a) >= 0.0f) continue;
          ProjectedTriangle& pt = setup[t];
          for (int k = 0; k < 3; ++k) {
            pt.p[k] = screen[tri[k]];
            pt.inv_z[k] = inv_z[tri[k]];
          }
          pt.index = t;
          pt.min_x = std::min({pt.p[0].x(), pt.p[1].x(), pt.p[2].x()});
          pt.max_x = std::max({pt.p[0].x(), pt.p[1].x(), pt.p[2].x()});
          pt.min_y = std::min({pt.p[0].y(), pt.p[1].y(), pt.p[2].y()});
          pt.max_y = std::max({pt.p[0].y(), pt.p[1].y(), pt.p[2].y()});
          kept[t] = !(pt.max_y < 0 || pt.min_y > height - 1);
        }
      },
      2048);

  // Each worker owns a band of rows, so no two threads write the same pixel.
  // Triangles are binned by band first (a counting sort that keeps their
  // order, so equal depths resolve as before), and a band visits only the
  // triangles that reach it.
  const int bands = std::max(1, std::min(height, worker_count() * 4));
  std::vector<int> band_of_row(height);
  for (int band = 0; band < bands; ++band)
    for (int y = height * band / bands; y < height * (band + 1) / bands; ++y) band_of_row[y] = band;
  const auto band_span = [&](const ProjectedTriangle& pt) {
    const int y0 = std::clamp(int(std::ceil(pt.min_y)), 0, height - 1);
    const int y1 = std::clamp(int(std::floor(pt.max_y)), 0, height - 1);
    return std::pair{band_of_row[y0], band_of_row[y1]};
  };
  std::vector<int> bin_offsets(bands + 1, 0);
  for (int t = 0; t < num_triangles; ++t) {
    if (!kept[t]) continue;
    const auto [b0, b1] = band_span(setup[t]);
    for (int band = b0; band <= b1; ++band) ++bin_offsets[band + 1];
  }
  for (int band = 0; band < bands; ++band) bin_offsets[band + 1] += bin_offsets[band];
  std::vector<int> bins(bin_offsets[bands]);
  // The box this call can draw in: the kept triangles' pixel bounds.
  int new_x0 = width, new_x1 = 0, new_y0 = height, new_y1 = 0;
  {
    std::vector<int> next(bin_offsets.begin(), bin_offsets.end() - 1);
    for (int t = 0; t < num_triangles; ++t) {
      if (!kept[t]) continue;
      const ProjectedTriangle& pt = setup[t];
      const auto [b0, b1] = band_span(pt);
      for (int band = b0; band <= b1; ++band) bins[next[band]++] = t;
      if (!(pt.max_x >= 0 && pt.min_x <= float(width - 1) && pt.max_y >= 0 && pt.min_y <= float(height - 1)))
        continue;  // draws nothing (NaN too)
      new_x0 = std::min(new_x0, std::max(0, int(std::ceil(pt.min_x))));
      new_x1 = std::max(new_x1, std::min(width - 1, int(std::floor(pt.max_x))) + 1);
      new_y0 = std::min(new_y0, std::max(0, int(std::ceil(pt.min_y))));
      new_y1 = std::max(new_y1, std::min(height - 1, int(std::floor(pt.max_y))) + 1);
    }
  }
  // What the last call drew goes back to the background; the rest is already.
  const int old_x0 = std::clamp(out.drawn_x0, 0, width), old_x1 = std::clamp(out.drawn_x1, 0, width);
  const int old_y0 = std::clamp(out.drawn_y0, 0, height), old_y1 = std::clamp(out.drawn_y1, 0, height);

  parallel_for(
      bands,
      [&](int band_begin, int band_end) {
        for (int band = band_begin; band < band_end; ++band) {
          const int y_lo = height * band / bands;
          const int y_hi = height * (band + 1) / bands - 1;
          for (int y = std::max(y_lo, old_y0); y < std::min(y_hi + 1, old_y1) && old_x0 < old_x1; ++y) {
            const size_t row = size_t(y) * width;
            std::fill(out.depth.begin() + row + old_x0, out.depth.begin() + row + old_x1,
                      std::numeric_limits<float>::infinity());
            std::fill(out.triangle.begin() + row + old_x0, out.triangle.begin() + row + old_x1, -1);
          }
          for (int k = bin_offsets[band]; k < bin_offsets[band + 1]; ++k) {
            const ProjectedTriangle& pt = setup[bins[k]];
            const Vec2f& p0 = pt.p[0];
            const Vec2f& p1 = pt.p[1];
            const Vec2f& p2 = pt.p[2];
            const float area = (p1.x() - p0.x()) * (p2.y() - p0.y()) - (p1.y() - p0.y()) * (p2.x() - p0.x());
            if (std::abs(area) < 1e-8f) continue;
            const float inv_area = 1.0f / area;
            const int x0 = std::max(0, int(std::ceil(pt.min_x)));
            const int x1 = std::min(width - 1, int(std::floor(pt.max_x)));
            const int y0 = std::max(y_lo, int(std::ceil(pt.min_y)));
            const int y1 = std::min(y_hi, int(std::floor(pt.max_y)));
            const CanonicalEdge e0(p1, p2), e1(p2, p0), e2(p0, p1);
            for (int y = y0; y <= y1; ++y) {
              const float py = float(y);
              const float r0 = e0.row(py), r1 = e1.row(py), r2 = e2.row(py);
              // Each edge's value, rounded, is monotone along the row, so the
              // pixels inside are one run: the row ends where it leaves them.
              bool entered = false;
              for (int x = x0; x <= x1; ++x) {
                const float px = float(x);
                // Screen-space barycentrics from edge functions.
                const float w0 = e0.at(r0, px) * inv_area;
                const float w1 = e1.at(r1, px) * inv_area;
                const float w2 = e2.at(r2, px) * inv_area;
                if (w0 < 0 || w1 < 0 || w2 < 0) {
                  if (entered) break;
                  continue;
                }
                entered = true;
                // Perspective-correct: interpolate 1/z linearly in screen space.
                const float iz = w0 * pt.inv_z[0] + w1 * pt.inv_z[1] + w2 * pt.inv_z[2];
                const float z = 1.0f / iz;
                const size_t idx = size_t(y) * width + x;
                if (z >= out.depth[idx]) continue;
                out.depth[idx] = z;
                out.triangle[idx] = pt.index;
                out.bary[idx] = Vec2f(w1 * pt.inv_z[1] * z, w2 * pt.inv_z[2] * z);
              }
            }
          }
        }
      },
      1);
  out.drawn_x0 = new_x0;
  out.drawn_x1 = std::max(new_x0, new_x1);
  out.drawn_y0 = new_y0;
  out.drawn_y1 = std::max(new_y0, new_y1);
}

std::vector<bool> vertex_visibility(const Positions& camera_points, const Positions& camera_normals,
                                    const PinholeCamera& camera, const RasterBuffers& buffers, float depth_tolerance) {
  const int n = static_cast<int>(camera_points.cols());
  std::vector<bool> visible(n, false);
  for (int i = 0; i < n; ++i) {
    const Vec3f p = camera_points.col(i);
    if (p.z() <= 0) continue;
    const float facing = view_facing(p, camera_normals.col(i));
    if (facing <= 0.0f) continue;  // faces away from the camera
    const Vec2f q = camera.project(p);
    const int x = int(std::lround(q.x()));
    const int y = int(std::lround(q.y()));
    if (x < 0 || y < 0 || x >= buffers.width || y >= buffers.height) continue;
    // The surface at the vertex's pixel centre lies up to sqrt(2)/2 px from
    // the vertex; on a slope seen at angle theta the depth changes by
    // (z / f) tan(theta) per pixel. A fixed tolerance alone rejected most of
    // a face's tilted skin (cheeks, nose sides) and all of it at half
    // resolution, where a pixel is twice as deep on the same slope.
    const float tan_view = std::sqrt(std::max(0.0f, 1.0f - facing * facing)) / facing;
    const float slope_allowance = 0.75f * float(p.z() / camera.focal) * std::min(tan_view, kMaxVisibilitySlope);
    const float surface = buffers.depth[size_t(y) * buffers.width + x];
    visible[i] = p.z() <= surface + depth_tolerance + slope_allowance;
  }
  return visible;
}

}  // namespace facecap
