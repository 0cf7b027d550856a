#pragma once
// A texture and its successive halvings (box-filtered, as mipmaps are), to
// be sampled at the density a view needs: read at a third of its texel
// density, as a 1024-texel face texture is by a face 300 px wide, a texture
// is a scatter of cache misses and its finest detail aliases.
#include <algorithm>
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/mesh.hpp"

namespace facecap {

class TextureLevels {
 public:
  TextureLevels() = default;
  // `texture`: any float type; halved until a side would drop below `min_size`.
  explicit TextureLevels(const cv::Mat& texture, int min_size = 64);

  bool empty() const { return levels_.empty(); }
  int count() const { return int(levels_.size()); }
  const cv::Mat& level(int k) const { return levels_[k]; }

  // Level k's coordinate (x or y) of the point at level-0 coordinate `c0`
  // (pixel centres at integers, as cv::resize's area halving keeps them).
  float to_level(int k, float c0, bool rows) const;

  // The level of detail where a pixel spans `texels_per_pixel` texels of
  // level 0: log2 of it, within the levels there are.
  float lod_for(float texels_per_pixel) const;

  // The texture at level-0 point (x0, y0) and level of detail `lod`: the
  // two levels around it read bilinearly and blended (trilinear), so that
  // a face coming nearer does not sharpen by a whole level at once.
  template <int N>
  cv::Vec<float, N> sample(float lod, float x0, float y0) const {
    const int k = std::clamp(int(lod), 0, count() - 1);
    const float t = std::clamp(lod - float(k), 0.0f, 1.0f);
    const cv::Vec<float, N> fine =
        sample_bilinear_channels<N>(levels_[k], to_level(k, x0, false), to_level(k, y0, true));
    if (t <= 0.0f || k + 1 >= count()) return fine;
    const cv::Vec<float, N> coarse =
        sample_bilinear_channels<N>(levels_[k + 1], to_level(k + 1, x0, false), to_level(k + 1, y0, true));
    return fine * (1.0f - t) + coarse * t;
  }

  // Asks the CPU to fetch what sample() at that point will read, some reads
  // ahead of it. A render reads the texture a pixel at a time; once the
  // frame's other work has evicted the texture from the caches, each read
  // waits for memory unless it was asked for ahead (a replay of a 720p
  // face's reads: 33 ns each in cache, 90-160 after 8-256 MB of other work,
  // 33-35 asked for 8 reads ahead).
  void prefetch(float lod, float x0, float y0) const {
    const int k = std::clamp(int(lod), 0, count() - 1);
    prefetch_level(k, x0, y0);
    if (lod > float(k) && k + 1 < count()) prefetch_level(k + 1, x0, y0);
  }

 private:
  // The two rows sample_bilinear_channels reads at level k's point.
  void prefetch_level(int k, float x0, float y0) const {
    const cv::Mat& l = levels_[k];
    const int x = std::clamp(int(to_level(k, x0, false)), 0, l.cols - 1);
    const int y = std::clamp(int(to_level(k, y0, true)), 0, std::max(0, l.rows - 2));
    __builtin_prefetch(l.ptr(y) + size_t(x) * l.elemSize());
    __builtin_prefetch(l.ptr(std::min(y + 1, l.rows - 1)) + size_t(x) * l.elemSize());
  }

  std::vector<cv::Mat> levels_;
};

// How many texels of a square texture `texture_size` wide a pixel spans where
// `mesh` (with UVs; `points` in camera space) is seen: the median over its
// triangles facing the camera of sqrt(UV area in texels / image area in
// pixels); 1 where none faces it.
float texels_per_pixel(const TriangleMesh& mesh, const Positions& points, const PinholeCamera& camera,
                       int texture_size);

}  // namespace facecap
