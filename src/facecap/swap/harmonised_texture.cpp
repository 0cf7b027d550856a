#include "facecap/swap/harmonised_texture.hpp"

#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/swap/brightness_hue.hpp"
#include "facecap/swap/chroma_spread.hpp"
#include "facecap/swap/face_swapper.hpp"
#include "facecap/swap/noise_matching.hpp"
#include "facecap/swap/skin_texture.hpp"

namespace facecap {

namespace {

// Per-vertex weighted means of a texture (each texel feeds its triangle's
// corners by its barycentric weights); `seen` receives each vertex's weight.
Positions vertex_means(const UvTexelMap& map, const std::vector<Triangle>& triangles, const cv::Mat& albedo,
                       const cv::Mat& weight, int num_vertices, std::vector<float>& seen) {
  Positions sum = Positions::Zero(3, num_vertices);
  seen.assign(num_vertices, 0.0f);
  for (int y = 0; y < map.size; ++y) {
    const auto* a = albedo.ptr<cv::Vec3f>(y);
    const float* w = weight.ptr<float>(y);
    for (int x = 0; x < map.size; ++x) {
      const int i = map.index(x, y);
      if (map.triangle[i] < 0 || w[x] <= 0) continue;
      const Triangle& t = triangles[map.triangle[i]];
      for (int k = 0; k < 3; ++k) {
        const float b = map.weights[i][k] * w[x];
        sum.col(t[k]) += b * Vec3f(a[x][0], a[x][1], a[x][2]);
        seen[t[k]] += b;
      }
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (seen[v] > 0) sum.col(v) /= seen[v];
  }
  return sum;
}

}  // namespace

HarmonisedTexture::HarmonisedTexture(const FaceModel& model, const cv::Mat& photo, const SourceFace& source,
                                     const TriangleMesh& skin, const SwapOptions& options)
    : skin_(skin),
      map_(rasterize_uv(skin, options.texture_size)),
      noise_sigma_(options.noise_sigma),
      match_grade_(options.match_grade) {
  const FaceTexture t = unshade_photo(model, photo, source.camera_points, source.camera, source.lighting, skin, map_,
                                      options.mirror_source ? options.mirror_low_pass_texels : 0.0);
  const cv::Mat source_albedo = fill_unseen(t.albedo, t.weight);
  std::vector<float> seen;
  source_vertex_albedo_ =
      vertex_means(map_, skin.triangles, source_albedo, cv::Mat(t.weight + 1e-3f), skin.num_vertices, seen);
  cv::GaussianBlur(source_albedo, source_smooth_, cv::Size(0, 0), noise_sigma_);
  if (options.photo_detail_gain != 1.0f)
    source_smooth_ = scale_detail(source_smooth_, options.photo_detail_fraction * map_.size, options.photo_detail_gain);
  // The residual holds the fine detail and the share of the mid-scale
  // detail the gain took out, both then mapped onto the target's fine-noise
  // histogram (eq. 6.5). The fine detail alone measured worse: self-swap
  // mean 5.748 -> 5.788 (address_720p_a), 8.881 -> 9.002 (_b).
  source_residual_ = source_albedo - source_smooth_;
  source_seen_ = t.weight > 0;
  // Alpha in UV space: distance (texels) to the nearest texel outside the skin.
  cv::Mat covered(map_.size, map_.size, CV_8U);
  for (int i = 0; i < map_.size * map_.size; ++i) covered.data[i] = map_.triangle[i] >= 0 ? 255 : 0;
  cv::Mat distance;
  cv::distanceTransform(covered, distance, cv::DIST_L2, 5);
  alpha_ = cv::min(distance / options.fade_texels, 1.0f);
  // smoothstep: no kink where the fade starts
  alpha_ = alpha_.mul(alpha_).mul(3.0f - 2.0f * alpha_);
}

void HarmonisedTexture::add_target_frame(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera,
                                         const ShCoeffs& lighting, const std::vector<std::vector<cv::Point>>& holes) {
  FaceTexture tex = unshade_face(frame, points, skin_.triangles, camera, lighting, map_, holes);
  drop_non_skin(tex);
  if (target_frames_ == 0) {
    target_first_ = tex;
    matched_noise_ = cv::Mat();
  }
  accumulate(target_sum_, tex);
  ++target_frames_;
  harmonise();
}

void HarmonisedTexture::restart() {
  target_frames_ = 0;
  target_sum_ = FaceTexture();
}

// Eq. 6.3-6.5 with the target frames seen so far.
void HarmonisedTexture::harmonise() {
  const FaceTexture target = weighted_mean(target_sum_);
  std::vector<float> seen_t;
  const Positions tgt = vertex_means(map_, skin_.triangles, target.albedo, target.weight, skin_.num_vertices, seen_t);
  std::vector<bool> known(skin_.num_vertices);
  for (int v = 0; v < skin_.num_vertices; ++v) known[v] = seen_t[v] > 0.05f;
  target_vertex_albedo_ = tgt;
  target_vertex_seen_ = seen_t;
  // Where none of the face's outline was seen in the target yet (a head
  // turned far away), the source albedo stays as it is until one is.
  // The adaptation's offset is taken on the albedos' brightness and hue
  // (brightness_hue.hpp), the source's hues first narrowed to the target's
  // grade (chroma_spread.hpp).
  const Positions source_yc = to_brightness_hue(source_vertex_albedo_), target_yc = to_brightness_hue(tgt);
  const ChromaSpread grade = match_grade_ ? ChromaSpread(source_yc, target_yc, known) : ChromaSpread();
  Positions offset = Positions::Zero(3, skin_.num_vertices);
  try {
    // Its factorisation serves again while the known outline is the same.
    if (!adaptation_ || !adaptation_->fixes_the_same(known))
      adaptation_.emplace(skin_.triangles, skin_.num_vertices, known);
    offset = adaptation_->offset(grade.narrow(source_yc), target_yc);
  } catch (const Error&) {
  }
  // Noise: the photo's fine residual, histogram-matched to the first target frame's.
  if (matched_noise_.empty()) {
    const cv::Mat residual_t = fine_residual(fill_unseen(target_first_.albedo, target_first_.weight), noise_sigma_);
    matched_noise_ =
        match_histograms(source_residual_, source_seen_, residual_t, target_first_.weight > 0, -0.3f, 0.3f);
  }
  // The harmonised colour on the skin's texels; the rest take their
  // neighbours' colour (fill_unseen), so that bilinear lookups at the
  // skin's edge stay clean, whatever is written there first.
  cv::Mat colour(map_.size, map_.size, CV_32FC3);
  parallel_for(
      map_.size,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          const auto* sm = source_smooth_.ptr<cv::Vec3f>(y);
          const auto* nm = matched_noise_.ptr<cv::Vec3f>(y);
          const float* al = alpha_.ptr<float>(y);
          auto* out = colour.ptr<cv::Vec3f>(y);
          for (int x = 0; x < map_.size; ++x) {
            if (!(al[x] > 0)) {
              out[x] = cv::Vec3f(0, 0, 0);
              continue;
            }
            const int i = map_.index(x, y);
            Vec3f yc = grade.narrow(to_brightness_hue(Vec3f(sm[x][0], sm[x][1], sm[x][2])));
            if (map_.triangle[i] >= 0) yc += map_.interpolate(skin_.triangles, offset, i);
            const Vec3f adapted = from_brightness_hue(yc);
            for (int c = 0; c < 3; ++c) out[x][c] = std::max(0.0f, adapted[c] + nm[x][c]);
          }
        }
      },
      32);
  cv::Mat inside;
  cv::Mat(alpha_ > 0).convertTo(inside, CV_32F, 1.0 / 255);
  std::vector<cv::Mat> channels;
  cv::split(fill_unseen(colour, inside), channels);
  channels.push_back(alpha_);
  cv::merge(channels, texture_);
  levels_ = TextureLevels(texture_);
}

}  // namespace facecap
