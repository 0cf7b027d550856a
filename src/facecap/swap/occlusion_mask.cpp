#include "facecap/swap/occlusion_mask.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/swap/weighted_channels.hpp"

namespace facecap {

namespace {

constexpr float kNone = std::numeric_limits<float>::max();

cv::Mat log_colour(const cv::Mat& bgr) {
  cv::Mat out;
  cv::log(cv::max(bgr, 0.02f), out);
  return out;
}

// A round structuring element `radius` texels across each way.
cv::Mat disc(int radius) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
}

int texels(float mm, double texels_per_mm) { return static_cast<int>(std::lround(mm * texels_per_mm)); }

}  // namespace

float cover_at(const cv::Mat& cover, const Vec2f& uv) {
  const Vec2f texel = uv_to_texel(uv, cover.cols);
  return sample_bilinear_channels<1>(cover, texel.x(), texel.y())[0];
}

cv::Mat cover_in_image(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size size,
                       const cv::Mat& cover) {
  RasterBuffers buffers;
  buffers.resize(size.width, size.height);
  rasterize(points, skin.triangles, camera, buffers);
  cv::Mat out(size, CV_32F, cv::Scalar(0));
  parallel_for(
      size.height,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          float* o = out.ptr<float>(y);
          for (int x = 0; x < size.width; ++x) {
            const size_t i = size_t(y) * size.width + x;
            const int tri = buffers.triangle[i];
            if (tri < 0) continue;
            o[x] = cover_at(cover, uv_at(skin, tri, buffers.bary[i]));
          }
        }
      },
      16);
  return out;
}

cv::Mat cover_in_front(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size size,
                       const cv::Mat& cover, int across_px) {
  cv::Mat in_front = cover_in_image(skin, points, camera, size, cover);
  const int across = std::max(1, across_px);
  cv::morphologyEx(in_front, in_front, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * across + 1, 2 * across + 1)));
  return in_front;
}

OcclusionMask::OcclusionMask(const TriangleMesh& skin, double mm_per_uv, OcclusionOptions options) : options_(options) {
  if (!(mm_per_uv > 0)) throw Error("occlusion mask: the mesh has no UV extent");
  if (!(options_.texel_mm > 0 && options_.min_log_change > 0 && options_.slide_mm >= 0 && options_.min_extent_mm >= 0 &&
        options_.unseen_mm >= 0 && options_.margin_mm >= 0 && options_.feather_mm >= 0))
    throw Error("occlusion mask: needs a positive texel size and change, and no negative distance");
  grid_ = millimetre_grid(skin, mm_per_uv, options_.texel_mm);
}

void OcclusionMask::clear_reference() { low_ = high_ = log_sum_ = weight_sum_ = cv::Mat(); }

void OcclusionMask::add_reference(const FaceTexture& seen) {
  const int n = grid_.map.size;
  if (low_.empty()) {
    low_ = cv::Mat(n, n, CV_32FC3, cv::Scalar::all(kNone));
    high_ = cv::Mat(n, n, CV_32FC3, cv::Scalar::all(-kNone));
    log_sum_ = cv::Mat(n, n, CV_32FC3, cv::Scalar::all(0));
    weight_sum_ = cv::Mat(n, n, CV_32F, cv::Scalar(0));
  }
  const cv::Mat log = log_colour(seen.albedo);
  const cv::Mat unseen = seen.weight <= 0;
  // This frame's least and most within slide_mm (unseen texels take no
  // part), folded into the envelope.
  cv::Mat low = log.clone(), high = log.clone();
  low.setTo(cv::Scalar::all(kNone), unseen);
  high.setTo(cv::Scalar::all(-kNone), unseen);
  const int slide = texels(options_.slide_mm, grid_.texels_per_mm);
  if (slide > 0) {
    cv::erode(low, low, disc(slide), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar::all(kNone));
    cv::dilate(high, high, disc(slide), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar::all(-kNone));
  }
  low_ = cv::min(low_, low);
  high_ = cv::max(high_, high);
  log_sum_ += times_weight(log, seen.weight);
  weight_sum_ += seen.weight;
}

cv::Mat OcclusionMask::covered(const FaceTexture& seen, const cv::Mat& moving) const {
  const int n = grid_.map.size;
  cv::Mat out(n, n, CV_32F, cv::Scalar(0));
  if (low_.empty() || seen.empty()) return out;
  const cv::Mat log = log_colour(seen.albedo);
  const cv::Mat both = (seen.weight > 0) & (weight_sum_ > 0);
  if (cv::countNonZero(both) < 50) return out;

  // The frame's overall shift: per channel, the median of its log colour
  // less the appearance frames' mean, over the texels both saw (every
  // third of them each way: a median needs no more).
  cv::Vec3f shift;
  {
    std::vector<float> values[3];
    for (int k = 0; k < 3; ++k) values[k].reserve(size_t(n) * n / 9 + n);
    for (int y = 0; y < n; y += 3) {
      const auto* l = log.ptr<cv::Vec3f>(y);
      const auto* s = log_sum_.ptr<cv::Vec3f>(y);
      const float* w = weight_sum_.ptr<float>(y);
      const uchar* b = both.ptr<uchar>(y);
      for (int x = 0; x < n; x += 3) {
        if (!b[x]) continue;
        for (int k = 0; k < 3; ++k) values[k].push_back(l[x][k] - s[x][k] / w[x]);
      }
    }
    for (int k = 0; k < 3; ++k) shift[k] = median_in_place(values[k]);
  }
  // Outside the envelope by more than min_log_change in some channel.
  cv::Mat found(n, n, CV_8U, cv::Scalar(0));
  for (int y = 0; y < n; ++y) {
    const auto* l = log.ptr<cv::Vec3f>(y);
    const auto* lo = low_.ptr<cv::Vec3f>(y);
    const auto* hi = high_.ptr<cv::Vec3f>(y);
    const float* w = seen.weight.ptr<float>(y);
    uchar* f = found.ptr<uchar>(y);
    for (int x = 0; x < n; ++x) {
      if (w[x] <= 0 || lo[x][0] == kNone) continue;
      float outside = 0;
      for (int k = 0; k < 3; ++k) {
        const float v = l[x][k] - shift[k];
        outside = std::max({outside, lo[x][k] - v, v - hi[x][k]});
      }
      if (outside > options_.min_log_change) f[x] = 255;
    }
  }
  if (!moving.empty()) found.setTo(255, (moving > kCoveringEvidence) & (seen.weight > 0));
  const int speck = texels(0.5f * options_.min_extent_mm, grid_.texels_per_mm);
  if (speck > 0) cv::morphologyEx(found, found, cv::MORPH_OPEN, disc(speck));
  if (cv::countNonZero(found) == 0) return out;
  // Gaps as wide as an edge's band, and what the frame does not see (turned
  // away at the chin, inside the mouth's outline) as far as unseen_mm from
  // a cover: the new face's outline differs from the target's, and may
  // show there.
  const int band = texels(options_.slide_mm + 2.0f, grid_.texels_per_mm);
  if (band > 0) cv::morphologyEx(found, found, cv::MORPH_CLOSE, disc(band));
  const cv::Mat unseen = seen.weight <= 0;
  for (int i = 0, reach = texels(options_.unseen_mm, grid_.texels_per_mm); i < reach; ++i) {
    cv::Mat grown;
    cv::dilate(found, grown, disc(1));
    found |= grown & unseen;
  }
  // What the covers enclose: all that the grid's border cannot reach.
  cv::Mat outside;
  cv::copyMakeBorder(found, outside, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::floodFill(outside, cv::Point(0, 0), 128);
  found.setTo(255, outside(cv::Rect(1, 1, n, n)) == 0);
  const int grow = texels(options_.margin_mm, grid_.texels_per_mm);
  if (grow > 0) cv::dilate(found, found, disc(grow));
  found.convertTo(out, CV_32F, 1.0 / 255);
  const double sigma = 0.5 * options_.feather_mm * grid_.texels_per_mm;
  if (sigma > 0) cv::GaussianBlur(out, out, cv::Size(0, 0), sigma);
  return out;
}

}  // namespace facecap
