#include "facecap/render/uv_bake.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"

namespace facecap {

UvBaker::UvBaker(const std::vector<Triangle>& triangles, const UvTexelMap& map, int grow_texels) : size_(map.size) {
  const int size = map.size;
  std::vector<unsigned char> reached(size_t(size) * size, 0);
  for (int i = 0; i < size * size; ++i) {
    if (map.triangle[i] < 0) continue;
    covered_.push_back(i);
    corners_.push_back(triangles[map.triangle[i]]);
    weights_.push_back(map.weights[i]);
    reached[i] = 1;
  }
  for (int r = 0; r < grow_texels; ++r) {
    Ring ring;
    ring.offsets.push_back(0);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        if (reached[map.index(x, y)]) continue;
        const size_t first = ring.sources.size();
        for (int ny = std::max(0, y - 1); ny <= std::min(size - 1, y + 1); ++ny)
          for (int nx = std::max(0, x - 1); nx <= std::min(size - 1, x + 1); ++nx)
            if (reached[map.index(nx, ny)]) ring.sources.push_back(map.index(nx, ny));
        if (ring.sources.size() == first) continue;
        ring.texels.push_back(map.index(x, y));
        ring.offsets.push_back(int(ring.sources.size()));
      }
    }
    for (const int t : ring.texels) reached[t] = 1;  // after the ring: a ring grows from the one before only
    rings_.push_back(std::move(ring));
  }
}

cv::Mat UvBaker::bake(const Eigen::MatrixXf& values) const {
  const int channels = int(values.rows());
  if (channels < 1 || channels > 4) throw Error("a UV bake takes 1 to 4 values per vertex");
  cv::Mat baked(size_, size_, CV_32FC(channels), cv::Scalar::all(0));
  auto* texels = baked.ptr<float>();
  const float* v = values.data();  // column-major: vertex j's channel c at j * channels + c
  for (size_t k = 0; k < covered_.size(); ++k) {
    const Triangle& t = corners_[k];
    const Vec3f& w = weights_[k];
    float* out = texels + size_t(covered_[k]) * channels;
    for (int c = 0; c < channels; ++c)
      out[c] = w[0] * v[t[0] * channels + c] + w[1] * v[t[1] * channels + c] + w[2] * v[t[2] * channels + c];
  }
  for (const Ring& ring : rings_) {
    for (size_t k = 0; k < ring.texels.size(); ++k) {
      float* out = texels + ring.texels[k] * channels;
      for (int c = 0; c < channels; ++c) {
        float m = texels[ring.sources[ring.offsets[k]] * channels + c];
        for (int s = ring.offsets[k] + 1; s < ring.offsets[k + 1]; ++s)
          m = std::max(m, texels[ring.sources[s] * channels + c]);
        out[c] = m;
      }
    }
  }
  return baked;
}

cv::Mat bake_uv_texture(const TriangleMesh& mesh, const Positions& values, int size) {
  const cv::Mat rgb = UvBaker(mesh.triangles, rasterize_uv(mesh, size)).bake(values);
  cv::Mat bgr, texture;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  bgr.convertTo(texture, CV_8UC3, 255.0);
  return texture;
}

}  // namespace facecap
