#include "facecap/swap/face_swapper.hpp"

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/compose/face_layer.hpp"
#include "facecap/compose/face_reshading.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/refine/refiner.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/render/texture_levels.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/albedo_adaptation.hpp"
#include "facecap/swap/background_warp.hpp"
#include "facecap/swap/brightness_hue.hpp"
#include "facecap/swap/chroma_spread.hpp"
#include "facecap/swap/expression_ratio.hpp"
#include "facecap/swap/face_render.hpp"
#include "facecap/swap/face_texture.hpp"
#include "facecap/swap/frame_preparation.hpp"
#include "facecap/swap/light_colour.hpp"
#include "facecap/swap/lit_vertices.hpp"
#include "facecap/swap/noise_matching.hpp"
#include "facecap/swap/occlusion_mask.hpp"
#include "facecap/swap/residual_shading.hpp"
#include "facecap/swap/size_match.hpp"
#include "facecap/swap/skin_texture.hpp"
#include "facecap/swap/weighted_channels.hpp"
#include "facecap/swap/wrinkle_transfer.hpp"

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

// `seen` (per vertex) with the vertices under a cover (any part of the
// OcclusionMask's grid `cover` above zero at one of their UVs) unseen: the
// frame's colour there is not the face's.
std::vector<float> uncovered(const TriangleMesh& mesh, std::vector<float> seen, const cv::Mat& cover) {
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (cover_at(cover, mesh.uvs[mesh.triangle_uvs[t][k]]) > 0) seen[mesh.triangles[t][k]] = 0;
    }
  }
  return seen;
}

// The points whose `keep` is set, in order.
std::vector<cv::Point2f> kept(const std::vector<cv::Point2f>& points, const std::vector<bool>& keep) {
  std::vector<cv::Point2f> out;
  for (size_t k = 0; k < points.size(); ++k)
    if (keep[k]) out.push_back(points[k]);
  return out;
}

// The eyes' and the mouth's outlines among the warp's anchors, whose first
// 68 are the landmarks (iBUG 36-41, 42-47 and 48-59).
std::vector<std::vector<cv::Point2f>> feature_outlines(const std::vector<cv::Point2f>& anchors) {
  if (anchors.size() < 60) return {};
  const auto run = [&](int first, int last) {
    return std::vector<cv::Point2f>(anchors.begin() + first, anchors.begin() + last + 1);
  };
  return {run(36, 41), run(42, 47), run(48, 59)};
}

// Multi-band blend (as the expression transformation's, §5.3.3) of the
// render over the warped background (both `out.window`-sized), with the
// alpha map as the mask: the coarse bands cross the outline smoothly, the
// fine ones keep it sharp.
void blend_face(const cv::Mat& background, const cv::Mat& render, SwappedFrame& out) {
  cv::Mat region = out.image(out.window);
  background.copyTo(region);
  FaceLayer layer;
  layer.box = out.window;
  layer.colour = background.clone();
  // The layer's colour is the render already mixed by alpha, so it has no
  // step where alpha starts: the pyramid's coarse bands, which reach past
  // the mask, would carry that step out to the blend's edge.
  for (int y = 0; y < out.window.height; ++y) {
    const auto* c = render.ptr<cv::Vec3f>(y);
    const float* a = out.alpha.ptr<float>(y);
    auto* o = layer.colour.ptr<cv::Vec3b>(y);
    for (int x = 0; x < out.window.width; ++x) {
      if (a[x] <= 0) continue;
      for (int k = 0; k < 3; ++k) o[x][k] = cv::saturate_cast<uchar>(a[x] * c[x][k] + (1 - a[x]) * o[x][k]);
    }
  }
  out.alpha.convertTo(layer.mask, CV_8U, 255.0);
  composite_layer(out.image, layer, 0, 1.0);
}

}  // namespace

struct FaceSwapper::Impl {
  const FaceModel& model;
  SwapOptions options;
  SourceFace source;
  TriangleMesh skin;
  UvTexelMap map;
  // The photo's side of eq. 6.3-6.5, fixed once the photo is unshaded: its
  // albedo per skin vertex, its texture above the noise scale (mid-scale
  // detail scaled by photo_detail_gain) and the rest, and where it was seen.
  Positions source_vertex_albedo;
  cv::Mat source_smooth;         // CV_32FC3
  cv::Mat source_residual;       // CV_32FC3: the filled albedo less source_smooth
  cv::Mat source_seen;           // CV_8U
  cv::Mat alpha;                 // CV_32F texture: 1 inside, fading to 0 at the skin's boundary
  cv::Mat texture;               // CV_32FC4: harmonised albedo (BGR) and alpha
  TextureLevels texture_levels;  // `texture` and its halvings, for the render
  FaceTexture target_sum;
  FaceTexture target_first;
  // The photo's fine residual histogram-matched to target_first's (eq. 6.5's
  // noise): it depends on nothing else, so the appearance frames after the
  // first reuse it. Empty until then.
  cv::Mat matched_noise;
  std::optional<AlbedoAdaptation> adaptation;  // the last appearance frame's (harmonise())
  int appearance_seen = 0;
  std::vector<int> anchors;                      // landmark and boundary vertices for the background warp
  std::vector<std::optional<Vec2f>> anchor_uvs;  // each anchor's UV on the skin (none off it)
  BackgroundWarp warp;
  // §6.1.2, built on the first refined target frame.
  std::unique_ptr<CoatingTransfer> coating;
  std::optional<ExpressionReference> reference;
  Positions reference_coating;      // xi_0^T
  std::vector<Triangle> fine_skin;  // the finest level's skin triangles
  // The identity shapes (neutral + B_id alpha over the face region), each
  // evaluated once: only the expression changes from frame to frame.
  Eigen::VectorXf source_identity_shape;
  Eigen::VectorXf target_identity;  // alpha^T the two below were computed for
  Eigen::VectorXf target_identity_shape;
  SizeMatch size;  // SwapOptions::match_target_size
  // The target's own albedo per skin vertex over the appearance frames, and
  // how much of each was seen: the reference for light_colour().
  Positions target_vertex_albedo;
  std::vector<float> target_vertex_seen;
  std::optional<ResidualShading> residual;  // SwapOptions::residual_shading_mm
  std::optional<ExpressionRatio> ratio;     // SwapOptions::expression_ratio
  std::optional<OcclusionMask> occlusion;   // SwapOptions::keep_occluders
  // With `occlusion`, where a frame comes without TargetFrame::prepared
  // (made on the first such frame: a swap's stream prepares its frames itself).
  std::unique_ptr<FramePreparation> preparation;

  // Follows the target's identity (fixed once its tracker has solved it).
  void update_target_identity(const Eigen::VectorXf& identity) {
    if (target_identity.size() == identity.size() && target_identity == identity) return;
    target_identity = identity;
    target_identity_shape = model.identity_shape(identity, regions::kFace);
    const Eigen::VectorXf none;  // no expression weights: the neutral faces
    size = match_size(model.with_expression(source_identity_shape, none, regions::kFace),
                      model.with_expression(target_identity_shape, none, regions::kFace));
  }

  Impl(const FaceModel& m, const cv::Mat& photo, SourceFace s, SwapOptions o)
      : model(m),
        options(o),
        source(std::move(s)),
        skin(skin_mesh(m)),
        map(rasterize_uv(skin, o.texture_size)),
        source_identity_shape(m.identity_shape(source.identity, regions::kFace)) {
    const FaceTexture t = unshade_photo(m, photo, source.camera_points, source.camera, source.lighting, skin, map,
                                        options.mirror_source ? options.mirror_low_pass_texels : 0.0);
    const cv::Mat source_albedo = fill_unseen(t.albedo, t.weight);
    std::vector<float> seen;
    source_vertex_albedo =
        vertex_means(map, skin.triangles, source_albedo, cv::Mat(t.weight + 1e-3f), skin.num_vertices, seen);
    cv::GaussianBlur(source_albedo, source_smooth, cv::Size(0, 0), options.noise_sigma);
    if (options.photo_detail_gain != 1.0f)
      source_smooth = scale_detail(source_smooth, options.photo_detail_fraction * map.size, options.photo_detail_gain);
    // The residual holds the fine detail and the share of the mid-scale
    // detail the gain took out, both then mapped onto the target's fine-noise
    // histogram (eq. 6.5). The fine detail alone measured worse: self-swap
    // mean 5.748 -> 5.788 (address_720p_a), 8.881 -> 9.002 (_b).
    source_residual = source_albedo - source_smooth;
    source_seen = t.weight > 0;
    // Alpha in UV space: distance (texels) to the nearest texel outside the skin.
    cv::Mat covered(map.size, map.size, CV_8U);
    for (int i = 0; i < map.size * map.size; ++i) covered.data[i] = map.triangle[i] >= 0 ? 255 : 0;
    cv::Mat distance;
    cv::distanceTransform(covered, distance, cv::DIST_L2, 5);
    alpha = cv::min(distance / options.fade_texels, 1.0f);
    // smoothstep: no kink where the fade starts
    alpha = alpha.mul(alpha).mul(3.0f - 2.0f * alpha);
    const std::vector<bool> boundary = boundary_vertices(skin.triangles, skin.num_vertices);
    if (options.residual_shading_mm > 0) {
      ResidualShadingOptions ro;
      ro.low_pass_mm = options.residual_shading_mm;
      residual.emplace(skin, model.with_expression(source_identity_shape, Eigen::VectorXf(), regions::kFace), ro);
    }
    const double mm_per_uv =
        millimetres_per_uv(skin, model.with_expression(source_identity_shape, Eigen::VectorXf(), regions::kFace));
    if (options.expression_ratio) ratio.emplace(skin, mm_per_uv);
    if (options.keep_occluders) occlusion.emplace(skin, mm_per_uv);
    // The warp's anchors: the landmarks and every second boundary vertex
    // (every third raised the seam ratio of Obama into address_720p_b,
    // 30 frames, 1.38 -> 1.43; every one lowered it to 1.36 for 0.7 ms more).
    anchors = model.landmarks.vertices;
    for (int v = 0, k = 0; v < skin.num_vertices; ++v) {
      if (boundary[v] && (k++ % 2 == 0)) anchors.push_back(v);
    }
    std::vector<std::optional<Vec2f>> vertex_uvs(skin.num_vertices);
    for (size_t t = 0; t < skin.triangles.size(); ++t)
      for (int c = 0; c < 3; ++c) {
        if (!vertex_uvs[skin.triangles[t][c]]) vertex_uvs[skin.triangles[t][c]] = skin.uvs[skin.triangle_uvs[t][c]];
      }
    for (const int v : anchors) anchor_uvs.push_back(v < skin.num_vertices ? vertex_uvs[v] : std::nullopt);
  }

  // Eq. 6.1-6.2: the target's fine motion since the reference frame, rotated
  // into the swapped mesh's tangent frames and solved for, shades the render:
  // each pixel is scaled by the SH shading of the wrinkled surface over that
  // of the coarse one (the texture already holds the photo's static detail).
  // Returns the milliseconds spent setting the transfer up (the first call).
  double add_wrinkles(const TargetFrame& target, const Positions& target_points, const Positions& swapped_points,
                      const PinholeCamera& window, cv::Mat& render) {
    const MeshHierarchy& h = *target.hierarchy;
    const int finest = h.num_levels() - 1;
    const MeshLevel& level = h.level(finest);
    if (target.fine.cols() != level.num_vertices) return 0.0;
    double setup_ms = 0;
    if (!coating) {
      const auto setup_start = std::chrono::steady_clock::now();
      coating = std::make_unique<CoatingTransfer>(level.triangles, level.num_vertices);
      reference.emplace(source.expression);
      std::vector<bool> skin_vertices(skin.num_vertices, false);
      for (const Triangle& tri : skin.triangles)
        for (int v : tri) skin_vertices[v] = true;
      fine_skin = masked_triangles(level.triangles, h.prolong_mask(skin_vertices, finest));
      setup_ms = ms_since(setup_start);
    }
    const Positions base_target = h.prolong_from_coarse(target_points, finest);
    const Positions base_swapped = h.prolong_from_coarse(swapped_points, finest);
    const Positions xi = coating->coating(target.fine, base_target);
    if (reference->offer(target.expression)) reference_coating = xi;
    const Positions swapped_normals = level_normals(level, base_swapped);
    const Positions motion =
        rotate_between_normals(xi - reference_coating, level_normals(level, base_target), swapped_normals);
    const Positions wrinkled = coating->solve(base_swapped, motion);
    const Positions wrinkled_normals = level_normals(level, wrinkled);
    RasterBuffers buffers;
    buffers.resize(render.cols, render.rows);
    rasterize(wrinkled, fine_skin, window, buffers);
    parallel_for(
        render.rows,
        [&](int y0, int y1) {
          for (int y = y0; y < y1; ++y) {
            auto* colour = render.ptr<cv::Vec3f>(y);
            for (int x = 0; x < render.cols; ++x) {
              const size_t i = size_t(y) * render.cols + x;
              if (buffers.triangle[i] < 0) continue;
              const Vec3f nw = to_viewer_frame(interpolate(buffers, fine_skin, wrinkled_normals, i).normalized());
              const Vec3f nc = to_viewer_frame(interpolate(buffers, fine_skin, swapped_normals, i).normalized());
              const float sc = sh_shade(target.lighting, nc.x(), nc.y(), nc.z());
              if (!(sc > 0.05f)) continue;
              const float ratio = std::clamp(sh_shade(target.lighting, nw.x(), nw.y(), nw.z()) / sc, 0.5f, 2.0f);
              colour[x] *= ratio;
            }
          }
        },
        16);
    return setup_ms;
  }

  // Eq. 6.3-6.5 with the target frames seen so far.
  void harmonise() {
    const FaceTexture target = weighted_mean(target_sum);
    std::vector<float> seen_t;
    const Positions tgt = vertex_means(map, skin.triangles, target.albedo, target.weight, skin.num_vertices, seen_t);
    std::vector<bool> known(skin.num_vertices);
    for (int v = 0; v < skin.num_vertices; ++v) known[v] = seen_t[v] > 0.05f;
    target_vertex_albedo = tgt;
    target_vertex_seen = seen_t;
    // Where none of the face's outline was seen in the target yet (a head
    // turned far away), the source albedo stays as it is until one is.
    // The adaptation's offset is taken on the albedos' brightness and hue
    // (brightness_hue.hpp), the source's hues first narrowed to the target's
    // grade (chroma_spread.hpp).
    const Positions source_yc = to_brightness_hue(source_vertex_albedo), target_yc = to_brightness_hue(tgt);
    const ChromaSpread grade = options.match_grade ? ChromaSpread(source_yc, target_yc, known) : ChromaSpread();
    Positions offset = Positions::Zero(3, skin.num_vertices);
    try {
      // Its factorisation serves again while the known outline is the same.
      if (!adaptation || !adaptation->fixes_the_same(known))
        adaptation.emplace(skin.triangles, skin.num_vertices, known);
      offset = adaptation->offset(grade.narrow(source_yc), target_yc);
    } catch (const Error&) {
    }
    // Noise: the photo's fine residual, histogram-matched to the first target frame's.
    if (matched_noise.empty()) {
      const cv::Mat residual_t =
          fine_residual(fill_unseen(target_first.albedo, target_first.weight), options.noise_sigma);
      matched_noise = match_histograms(source_residual, source_seen, residual_t, target_first.weight > 0, -0.3f, 0.3f);
    }
    const cv::Mat& matched = matched_noise;
    // The harmonised colour on the skin's texels; the rest take their
    // neighbours' colour (fill_unseen), so that bilinear lookups at the
    // skin's edge stay clean, whatever is written there first.
    cv::Mat colour(map.size, map.size, CV_32FC3);
    parallel_for(
        map.size,
        [&](int y0, int y1) {
          for (int y = y0; y < y1; ++y) {
            const auto* sm = source_smooth.ptr<cv::Vec3f>(y);
            const auto* nm = matched.ptr<cv::Vec3f>(y);
            const float* al = alpha.ptr<float>(y);
            auto* out = colour.ptr<cv::Vec3f>(y);
            for (int x = 0; x < map.size; ++x) {
              if (!(al[x] > 0)) {
                out[x] = cv::Vec3f(0, 0, 0);
                continue;
              }
              const int i = map.index(x, y);
              Vec3f yc = grade.narrow(to_brightness_hue(Vec3f(sm[x][0], sm[x][1], sm[x][2])));
              if (map.triangle[i] >= 0) yc += map.interpolate(skin.triangles, offset, i);
              const Vec3f adapted = from_brightness_hue(yc);
              for (int c = 0; c < 3; ++c) out[x][c] = std::max(0.0f, adapted[c] + nm[x][c]);
            }
          }
        },
        32);
    cv::Mat inside;
    cv::Mat(alpha > 0).convertTo(inside, CV_32F, 1.0 / 255);
    std::vector<cv::Mat> channels;
    cv::split(fill_unseen(colour, inside), channels);
    channels.push_back(alpha);
    cv::merge(channels, texture);
    texture_levels = TextureLevels(texture);
  }

  // TargetFrame::lighting_final: what was gathered under provisional lighting starts again.
  void restart_appearance() {
    appearance_seen = 0;
    target_sum = FaceTexture();
    if (ratio) ratio->clear_reference();
    if (occlusion) occlusion->clear_reference();
  }

  std::unique_ptr<FramePreparation> new_preparation() const {
    if (!occlusion) return nullptr;
    return std::make_unique<FramePreparation>(model, skin, occlusion->grid(), options.moving_covers);
  }

  // What covers the target face (occlusion_mask.hpp, on `occlusion`'s grid),
  // and the face's skin texture seen in the frame with the covers left out,
  // which the expression ratio can use on the same grid.
  struct Cover {
    cv::Mat cover;
    std::optional<FaceTexture> skin;
  };
  Cover find_cover(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                   bool appearance_frame) {
    PreparedFrame own;
    const PreparedFrame* prepared = target.prepared;
    if (!prepared) {
      if (!preparation) preparation = new_preparation();
      own = preparation->prepare(frame, target_points, target.camera, target.lighting, target.index);
      prepared = &own;
    }
    const FaceTexture& seen = prepared->seen;
    Cover c;
    c.skin = FaceTexture{seen.albedo, seen.weight.clone()};
    drop_non_skin(*c.skin);
    if (appearance_frame) occlusion->add_reference(seen);
    c.cover = occlusion->covered(seen, prepared->moving);
    c.skin->weight.setTo(0, c.cover > 0);  // the expression ratio's change is the face's, not a cover's
    return c;
  }

  // The target's fine change of appearance since its first frames, as
  // gains in the texture's layout (expression_ratio.hpp).
  cv::Mat expression_gains(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                           const std::vector<std::vector<cv::Point>>& holes,
                           const std::optional<FaceTexture>& uncovered_skin, bool appearance_frame) {
    const FaceTexture now = uncovered_skin && occlusion->grid_size() == ratio->grid_size()
                                ? *uncovered_skin
                                : ratio->unshade(frame, target_points, target.camera, target.lighting, holes);
    if (appearance_frame) ratio->add_reference(now);
    return ratio->gains(now);
  }

  // One of the first frames: its unshaded texture joins the target's
  // appearance, and the source's texture is harmonised again (eq. 6.3-6.5).
  void add_appearance_frame(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                            const std::vector<std::vector<cv::Point>>& holes) {
    FaceTexture tex = unshade_face(frame, target_points, skin.triangles, target.camera, target.lighting, map, holes);
    drop_non_skin(tex);
    if (appearance_seen == 0) {
      target_first = tex;
      matched_noise = cv::Mat();
    }
    accumulate(target_sum, tex);
    ++appearance_seen;
    harmonise();
  }

  // The target light's colour now against the appearance frames'
  // (light_colour.hpp) and the shading pattern its SH lighting leaves
  // unexplained (residual_shading.hpp), from the same lit vertices.
  FaceLight target_light(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                         const Positions& target_normals, const cv::Mat& cover) const {
    FaceLight light;
    if (target_vertex_albedo.cols() == 0 || !(options.follow_light_colour || residual)) return light;
    const std::vector<LitVertex> lit =
        lit_vertices(frame, target_points, target_normals,
                     cover.empty() ? target_vertex_seen : uncovered(skin, target_vertex_seen, cover), target.camera,
                     target.lighting);
    if (options.follow_light_colour) light.tint = light_colour(lit, target_vertex_albedo);
    if (residual) light.residual_gains = residual->gains(lit, target_vertex_albedo);
    return light;
  }

  // §6.3: the target background in `window`, warped to the swapped face's outline.
  cv::Mat warped_background(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                            const Positions& target_normals, const Positions& swapped_points,
                            const Positions& swapped_normals, const cv::Mat& cover, const cv::Rect& window) {
    const std::vector<cv::Point2f> from = project_vertices(target_points, anchors, target.camera);
    std::vector<cv::Point2f> to = project_vertices(swapped_points, anchors, target.camera);
    // What covers an anchor holds still, beyond the face's outline too
    // (the rest of a hand, a microphone's stand).
    for (size_t k = 0; k < to.size() && !cover.empty(); ++k) {
      if (anchor_uvs[k] && cover_at(cover, *anchor_uvs[k]) > 0.5f) to[k] = from[k];
    }
    const std::vector<bool> shown =
        anchors_facing(anchors, target_points, target_normals, swapped_points, swapped_normals, skin.num_vertices);
    cv::Mat background;
    warp.warp(frame, kept(from, shown), kept(to, shown), window, background, feature_outlines(to));
    return background;
  }

  // The covers stay in front, where the frame has them: neither the new
  // face nor the background's warp moves them. `out` (its image, alpha and
  // covered share) loses the new face where `cover` says.
  void keep_covers_in_front(const cv::Mat& frame, const Positions& target_points, const PinholeCamera& window,
                            const cv::Mat& cover, SwappedFrame& out) const {
    cv::Mat in_front = cover_in_image(skin, target_points, window, out.window.size(), cover);
    // Across the openings of the skin mesh (the mouth, the eyes) where a
    // cover lies on both sides of them: up to 6 % of the window each way
    // (the window is about 1.4 face widths: some 12 mm).
    const int across = std::max(1, cvRound(0.06 * out.window.width));
    cv::morphologyEx(in_front, in_front, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * across + 1, 2 * across + 1)));
    const double full = cv::sum(out.alpha)[0];
    out.alpha = out.alpha.mul(1.0f - in_front);
    out.covered = full > 0 ? 1.0 - cv::sum(out.alpha)[0] / full : 0.0;
    if (out.covered > 0) {
      cv::Mat swapped_f, frame_f;
      out.image(out.window).convertTo(swapped_f, CV_32FC3);
      frame(out.window).convertTo(frame_f, CV_32FC3);
      const cv::Mat mixed = swapped_f + times_weight(frame_f - swapped_f, in_front);
      mixed.convertTo(out.image(out.window), CV_8UC3);
    }
  }
};

FaceSwapper::FaceSwapper(const FaceModel& model, const cv::Mat& photo, SourceFace source, SwapOptions options)
    : impl_(std::make_unique<Impl>(model, photo, std::move(source), options)) {}
FaceSwapper::~FaceSwapper() = default;
FaceSwapper::FaceSwapper(FaceSwapper&&) noexcept = default;
FaceSwapper& FaceSwapper::operator=(FaceSwapper&&) noexcept = default;

cv::Mat FaceSwapper::harmonised_texture() const {
  if (impl_->texture.empty()) return {};
  std::vector<cv::Mat> ch;
  cv::split(impl_->texture, ch);
  cv::Mat bgr, out;
  cv::merge(std::vector<cv::Mat>{ch[0], ch[1], ch[2]}, bgr);
  bgr.convertTo(out, CV_8UC3, 255.0);
  return out;
}

std::optional<SizeMatch> FaceSwapper::size_match() const {
  if (!impl_->options.match_target_size || impl_->target_identity.size() == 0) return std::nullopt;
  return impl_->size;
}

std::unique_ptr<FramePreparation> FaceSwapper::make_preparation() const { return impl_->new_preparation(); }

SwappedFrame FaceSwapper::swap(const cv::Mat& frame, const TargetFrame& target, SwapTimings* timings) {
  Impl& m = *impl_;
  SwapTimings local;
  SwapTimings& t = timings ? *timings : local;
  const auto start = std::chrono::steady_clock::now();
  m.update_target_identity(target.identity);
  const bool given_points = target.points && target.points->cols() == m.target_identity_shape.size() / 3;
  const Positions target_points =
      given_points
          ? *target.points
          : to_camera(m.model.with_expression(m.target_identity_shape, target.expression, regions::kFace), target.pose);
  // §6.1.1: the source identity performing the target expression, under the target pose (eq. 6.6).
  Positions source_shape = m.model.with_expression(m.source_identity_shape, target.expression, regions::kFace);
  if (m.options.match_target_size) source_shape = m.size.apply(source_shape);
  const Positions swapped_points = to_camera(source_shape, target.pose);

  // What was gathered under provisional lighting starts again (TargetFrame::lighting_final).
  if (!target.lighting_final) m.restart_appearance();
  const std::vector<std::vector<cv::Point>> holes = feature_holes(m.model, target_points, target.camera);
  const bool appearance_frame = m.appearance_seen < m.options.appearance_frames;
  auto t0 = std::chrono::steady_clock::now();
  const Impl::Cover cover = m.occlusion ? m.find_cover(frame, target, target_points, appearance_frame) : Impl::Cover{};
  const double occlusion_ms = m.occlusion ? ms_since(t0) : 0.0;
  t.occlusion_ms += occlusion_ms;
  t0 = std::chrono::steady_clock::now();
  const cv::Mat ratio_gains =
      m.ratio ? m.expression_gains(frame, target, target_points, holes, cover.skin, appearance_frame) : cv::Mat();
  const double ratio_ms = m.ratio ? ms_since(t0) : 0.0;
  t.ratio_ms += ratio_ms;
  t0 = std::chrono::steady_clock::now();
  if (appearance_frame) m.add_appearance_frame(frame, target, target_points, holes);
  const double appearance_ms = ms_since(t0);
  t.appearance_ms += appearance_ms;

  const Positions target_normals = vertex_normals(target_points, m.skin.triangles);
  FaceLight light = m.target_light(frame, target, target_points, target_normals, cover.cover);
  light.expression_gains = ratio_gains;

  SwappedFrame out;
  out.image = frame.clone();
  const cv::Rect bounds =
      projected_bounds(swapped_points, target.camera) | projected_bounds(target_points, target.camera);
  const int margin = std::max(16, bounds.width / 5);
  out.window = cv::Rect(bounds.x - margin, bounds.y - margin, bounds.width + 2 * margin, bounds.height + 2 * margin) &
               cv::Rect(0, 0, frame.cols, frame.rows);
  if (out.window.area() == 0) return out;

  const PinholeCamera window = target.camera.cropped(out.window.x, out.window.y);
  const Positions normals = vertex_normals(swapped_points, m.skin.triangles);
  cv::Mat render =
      render_swapped_face(m.skin, m.texture_levels, swapped_points, normals, target.camera, window, out.window.size(),
                          target.lighting, light, m.options.silhouette_fade_start, out.alpha);
  t.render_ms += ms_since(start) - appearance_ms - ratio_ms - occlusion_ms;

  if (m.options.wrinkles && target.hierarchy && target.hierarchy->num_levels() > 1 && target.fine.cols() > 0) {
    t0 = std::chrono::steady_clock::now();
    const double setup_ms = m.add_wrinkles(target, target_points, swapped_points, window, render);
    t.wrinkle_setup_ms += setup_ms;
    t.wrinkle_ms += ms_since(t0) - setup_ms;
  }

  t0 = std::chrono::steady_clock::now();
  const cv::Mat background = m.options.warp_background
                                 ? m.warped_background(frame, target, target_points, target_normals, swapped_points,
                                                       normals, cover.cover, out.window)
                                 : frame(out.window).clone();
  t.warp_ms += ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  blend_face(background, render, out);
  t.blend_ms += ms_since(t0);

  if (!cover.cover.empty() && cv::countNonZero(cover.cover) > 0) {
    t0 = std::chrono::steady_clock::now();
    m.keep_covers_in_front(frame, target_points, window, cover.cover, out);
    t.occlusion_ms += ms_since(t0);
  }
  return out;
}

}  // namespace facecap
