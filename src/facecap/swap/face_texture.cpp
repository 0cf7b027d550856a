#include "facecap/swap/face_texture.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_reshading.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/swap/noise_matching.hpp"
#include "facecap/swap/weighted_channels.hpp"
#include "facecap/swap/wide_blur.hpp"

namespace facecap {

FaceTexture unshade_face(const cv::Mat& image, const Positions& camera_points, const std::vector<Triangle>& triangles,
                         const PinholeCamera& camera, const ShCoeffs& lighting, const UvTexelMap& map,
                         const std::vector<std::vector<cv::Point>>& excluded) {
  // Depth of the visible surface, rasterised into the face's window.
  const cv::Rect box = projected_bounds(camera_points, camera) & cv::Rect(0, 0, image.cols, image.rows);
  const PinholeCamera window = camera.cropped(box.x, box.y);
  RasterBuffers buffers;
  buffers.resize(std::max(1, box.width), std::max(1, box.height));
  rasterize(camera_points, triangles, window, buffers);
  const Positions normals = vertex_normals(camera_points, triangles);
  // The excluded polygons in the window, grown by 2 px (eyelashes, lip edges).
  cv::Mat holes(buffers.height, buffers.width, CV_8U, cv::Scalar(0));
  if (!excluded.empty()) {
    cv::fillPoly(holes, excluded, cv::Scalar(255), cv::LINE_8, 0, cv::Point(-box.x, -box.y));
    cv::dilate(holes, holes, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  }

  FaceTexture out;
  out.albedo = cv::Mat(map.size, map.size, CV_32FC3, cv::Scalar::all(0));
  out.weight = cv::Mat(map.size, map.size, CV_32F, cv::Scalar(0));
  parallel_for(
      map.size,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* albedo = out.albedo.ptr<cv::Vec3f>(y);
          auto* weight = out.weight.ptr<float>(y);
          for (int x = 0; x < map.size; ++x) {
            const int i = map.index(x, y);
            if (map.triangle[i] < 0) continue;
            const Vec3f p = map.interpolate(triangles, camera_points, i);
            const Vec3f n = map.interpolate(triangles, normals, i).normalized();
            const float facing = view_facing(p, n);
            if (!(facing > 0.2f)) continue;
            const Vec2f q = window.project(p);
            const int px = static_cast<int>(std::lround(q.x())), py = static_cast<int>(std::lround(q.y()));
            if (px < 0 || py < 0 || px >= buffers.width || py >= buffers.height) continue;
            if (p.z() > buffers.depth[size_t(py) * buffers.width + px] + 0.3f) continue;  // hidden
            if (holes.at<uchar>(py, px)) continue;
            const Vec2f qi = camera.project(p);
            const Vec3f rgb = sample_bilinear_rgb8(image, qi.x(), qi.y());
            const Vec3f nv = to_viewer_frame(n);
            const float shade = sh_shade(lighting, nv.x(), nv.y(), nv.z());
            if (!(shade > 0.05f)) continue;
            albedo[x] = cv::Vec3f(rgb.z() / shade, rgb.y() / shade, rgb.x() / shade);
            weight[x] = facing;
          }
        }
      },
      32);
  return out;
}

int drop_non_skin(FaceTexture& texture, float max_chroma, float max_log_brightness) {
  // Median chromaticity (b, g share of the sum) and brightness over the seen
  // texels, from every `stride`-th each way: some 4000 of them, as a median
  // needs no more (a face's occlusion grid sees 40k, an appearance texture
  // 600k).
  const int seen = cv::countNonZero(texture.weight > 0);
  const int stride = std::max(1, static_cast<int>(std::sqrt(seen / 4096.0)));
  std::vector<float> cb, cg, lum;
  for (int y = 0; y < texture.albedo.rows; y += stride) {
    const auto* a = texture.albedo.ptr<cv::Vec3f>(y);
    const float* w = texture.weight.ptr<float>(y);
    for (int x = 0; x < texture.albedo.cols; x += stride) {
      const float sum = a[x][0] + a[x][1] + a[x][2];
      if (w[x] <= 0 || sum <= 1e-4f) continue;
      cb.push_back(a[x][0] / sum);
      cg.push_back(a[x][1] / sum);
      lum.push_back(sum);
    }
  }
  if (cb.empty()) return 0;
  const float mb = median_in_place(cb), mg = median_in_place(cg), ml = median_in_place(lum);
  int dropped = 0;
  for (int y = 0; y < texture.albedo.rows; ++y) {
    const auto* a = texture.albedo.ptr<cv::Vec3f>(y);
    float* w = texture.weight.ptr<float>(y);
    for (int x = 0; x < texture.albedo.cols; ++x) {
      if (w[x] <= 0) continue;
      const float sum = a[x][0] + a[x][1] + a[x][2];
      const float chroma = std::hypot(a[x][0] / std::max(sum, 1e-4f) - mb, a[x][1] / std::max(sum, 1e-4f) - mg);
      if (chroma > max_chroma || std::abs(std::log(std::max(sum, 1e-4f) / ml)) > max_log_brightness) {
        w[x] = 0;
        ++dropped;
      }
    }
  }
  return dropped;
}

void complete_from_mirror(FaceTexture& texture, double low_pass_texels) {
  const cv::Mat albedo = texture.albedo.clone(), weight = texture.weight.clone();
  // Low-pass colour of what was seen: blur(albedo * weight) / blur(weight).
  cv::Mat low = wide_blur(times_weight(albedo, weight), low_pass_texels);
  const cv::Mat low_weight = wide_blur(weight, low_pass_texels);
  divide_by_weight(low, low_weight, 1e-4f);
  // Where this side saw too little around a texel (its low-pass weight, the
  // seen share of the neighbourhood), the mirror's colour is kept as it is:
  // this side's low-pass colour says too little there. A texel unseen itself
  // but with seen neighbours takes their colour: copied as it is, the other
  // side's colour came with its own lighting residual (a lit outer eye corner
  // copied into the dropped shadow of the other: a pale patch on the eyelid
  // when the target blinks).
  constexpr float kMinLowPassWeight = 0.05f;
  const int n = texture.albedo.cols;
  for (int y = 0; y < texture.albedo.rows; ++y) {
    const auto* a = albedo.ptr<cv::Vec3f>(y);
    const auto* lo = low.ptr<cv::Vec3f>(y);
    const float* w = weight.ptr<float>(y);
    const float* lw = low_weight.ptr<float>(y);
    auto* out = texture.albedo.ptr<cv::Vec3f>(y);
    float* out_w = texture.weight.ptr<float>(y);
    for (int x = 0; x < n; ++x) {
      const int m = n - 1 - x;
      const float extra = w[m] - w[x];
      if (extra <= 0) continue;
      cv::Vec3f mirrored = a[m];
      if (lw[x] > kMinLowPassWeight)
        for (int c = 0; c < 3; ++c) mirrored[c] *= lo[x][c] / std::max(lo[m][c], 1e-4f);
      out[x] = (w[x] * a[x] + extra * mirrored) / w[m];
      out_w[x] = w[m];
    }
  }
}

cv::Mat scale_detail(const cv::Mat& albedo, double sigma, float gain) {
  return albedo - (1.0f - gain) * fine_residual(albedo, sigma);
}

void accumulate(FaceTexture& sum, const FaceTexture& one) {
  const cv::Mat weighted = times_weight(one.albedo, one.weight);
  if (sum.empty()) {
    sum.albedo = weighted;
    sum.weight = one.weight.clone();
    return;
  }
  sum.albedo += weighted;
  sum.weight += one.weight;
}

FaceTexture weighted_mean(const FaceTexture& sum) {
  FaceTexture out;
  out.albedo = sum.albedo.clone();
  divide_by_weight(out.albedo, sum.weight, 1e-6f);
  out.weight = sum.weight.clone();
  return out;
}

cv::Mat fill_unseen(const cv::Mat& albedo, const cv::Mat& weight) {
  // Push: halve resolution with weighted means until every texel is covered.
  std::vector<cv::Mat> colour{albedo.clone()}, known{cv::Mat(weight > 0) / 255};
  known[0].convertTo(known[0], CV_32F);
  while (colour.back().cols > 2 && cv::countNonZero(known.back()) < static_cast<int>(known.back().total())) {
    cv::Mat c, k;
    cv::resize(times_weight(colour.back(), known.back()), c, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::resize(known.back(), k, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    divide_by_weight(c, k, 1e-6f);
    cv::threshold(k, k, 1e-6, 1.0, cv::THRESH_BINARY);
    colour.push_back(c);
    known.push_back(k);
  }
  // Pull: each level's holes take the coarser level's colour.
  for (int l = static_cast<int>(colour.size()) - 2; l >= 0; --l) {
    cv::Mat up;
    cv::resize(colour[l + 1], up, colour[l].size(), 0, 0, cv::INTER_LINEAR);
    up.copyTo(colour[l], known[l] == 0);
  }
  return colour[0];
}

}  // namespace facecap
