#include "facecap/refine/vertex_samples.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
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

namespace {

using ByteMask = std::vector<unsigned char>;

ByteMask to_bytes(const std::vector<bool>& mask) { return ByteMask(mask.begin(), mask.end()); }

std::vector<bool> to_bits(const ByteMask& mask) { return std::vector<bool>(mask.begin(), mask.end()); }

// Vertices per block of the ring passes (a finest level has about 37k).
constexpr int kRingBlock = 4096;

// `rings` passes over a mask, each computing every vertex's next value with
// rule(i, mask, pass) from the last pass's mask, on the pool.
template <typename Rule>
ByteMask ring_passes(ByteMask mask, int rings, const Rule& rule) {
  ByteMask next(mask.size());
  for (int r = 0; r < rings; ++r) {
    parallel_for(
        static_cast<int>(mask.size()),
        [&](int b, int e) {
          for (int i = b; i < e; ++i) next[i] = rule(i, mask, r);
        },
        kRingBlock);
    mask.swap(next);
  }
  return mask;
}

}  // namespace

// On bytes, not the bit-packed vector: the passes read every ring.
void erode_observations(VertexSamples& s, const VertexAdjacency& adjacency, int rings,
                        const std::vector<bool>& open_boundary) {
  const ByteMask seen = ring_passes(to_bytes(s.visible), rings, [&](int i, const ByteMask& m, int r) {
    bool keep = m[i] != 0;
    if (keep && r == 0 && !open_boundary.empty() && open_boundary[i]) keep = false;  // one ring from the hole
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1] && keep; ++k) keep = m[adjacency.indices[k]] != 0;
    return keep;
  });
  s.visible = to_bits(seen);
  s.visible_count = static_cast<int>(std::count(seen.begin(), seen.end(), 1));
}

std::vector<bool> grow_by_rings(const std::vector<bool>& mask, const VertexAdjacency& adjacency, int rings) {
  // A vertex joins when it or a neighbour is in (the rings are symmetric).
  return to_bits(ring_passes(to_bytes(mask), rings, [&](int i, const ByteMask& m, int) {
    bool grown = m[i] != 0;
    for (int k = adjacency.offsets[i]; k < adjacency.offsets[i + 1] && !grown; ++k)
      grown = m[adjacency.indices[k]] != 0;
    return grown;
  }));
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

}  // namespace facecap
