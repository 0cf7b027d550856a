#include "facecap/swap/face_swapper.hpp"

#include <chrono>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/compose/face_layer.hpp"
#include "facecap/compose/face_reshading.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/background_warp.hpp"
#include "facecap/swap/expression_ratio.hpp"
#include "facecap/swap/face_covers.hpp"
#include "facecap/swap/face_render.hpp"
#include "facecap/swap/face_texture.hpp"
#include "facecap/swap/frame_preparation.hpp"
#include "facecap/swap/harmonised_texture.hpp"
#include "facecap/swap/light_colour.hpp"
#include "facecap/swap/lit_vertices.hpp"
#include "facecap/swap/occlusion_mask.hpp"
#include "facecap/swap/residual_shading.hpp"
#include "facecap/swap/size_match.hpp"
#include "facecap/swap/skin_texture.hpp"
#include "facecap/swap/weighted_channels.hpp"
#include "facecap/swap/wrinkle_shading.hpp"

namespace facecap {

namespace {

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
  HarmonisedTexture texture;                     // the photo's, harmonised with the target (eq. 6.3-6.5)
  WrinkleShading wrinkles;                       // SwapOptions::wrinkles (§6.1.2)
  std::vector<int> anchors;                      // landmark and boundary vertices for the background warp
  std::vector<std::optional<Vec2f>> anchor_uvs;  // each anchor's UV on the skin (none off it)
  BackgroundWarp warp;
  // The identity shapes (neutral + B_id alpha over the face region), each
  // evaluated once: only the expression changes from frame to frame.
  Eigen::VectorXf source_identity_shape;
  Eigen::VectorXf target_identity;  // alpha^T the two below were computed for
  Eigen::VectorXf target_identity_shape;
  SizeMatch size;                           // SwapOptions::match_target_size
  std::optional<ResidualShading> residual;  // SwapOptions::residual_shading_mm
  std::optional<ExpressionRatio> ratio;     // SwapOptions::expression_ratio
  std::optional<FaceCovers> covers;         // SwapOptions::keep_occluders
  // With `covers`, where a frame comes without TargetFrame::prepared
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
        texture(m, photo, source, skin, o),
        wrinkles(skin, source.expression),
        source_identity_shape(m.identity_shape(source.identity, regions::kFace)) {
    const std::vector<bool> boundary = boundary_vertices(skin.triangles, skin.num_vertices);
    if (options.residual_shading_mm > 0) {
      ResidualShadingOptions ro;
      ro.low_pass_mm = options.residual_shading_mm;
      residual.emplace(skin, model.with_expression(source_identity_shape, Eigen::VectorXf(), regions::kFace), ro);
    }
    const double mm_per_uv =
        millimetres_per_uv(skin, model.with_expression(source_identity_shape, Eigen::VectorXf(), regions::kFace));
    if (options.expression_ratio) ratio.emplace(skin, mm_per_uv);
    if (options.keep_occluders) {
      // The appearance frames are the covers' references too.
      covers.emplace(model, skin, CoverOptions{true, options.moving_covers, options.appearance_frames}, mm_per_uv);
    }
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

  // TargetFrame::lighting_final: what was gathered under provisional
  // lighting starts again (the covers' references too, in FaceCovers::covered).
  void restart_appearance() {
    texture.restart();
    if (ratio) ratio->clear_reference();
  }

  std::unique_ptr<FramePreparation> new_preparation() const { return covers ? covers->new_preparation() : nullptr; }

  // What covers the target face (face_covers.hpp, on `covers`' grid),
  // and the face's skin texture seen in the frame with the covers left out,
  // which the expression ratio can use on the same grid.
  struct Cover {
    cv::Mat cover;
    std::optional<FaceTexture> skin;
    bool motion_measured = false;  // PreparedFrame's
  };
  Cover find_cover(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points) {
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
    c.cover = covers->covered(*prepared, target.lighting_final);
    c.motion_measured = prepared->motion_measured;
    c.skin->weight.setTo(0, c.cover > 0);  // the expression ratio's change is the face's, not a cover's
    return c;
  }

  // The target's fine change of appearance since its first frames, as
  // gains in the texture's layout (expression_ratio.hpp).
  cv::Mat expression_gains(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                           const std::vector<std::vector<cv::Point>>& holes,
                           const std::optional<FaceTexture>& uncovered_skin, bool appearance_frame) {
    const FaceTexture now = uncovered_skin && covers->grid().map.size == ratio->grid_size()
                                ? *uncovered_skin
                                : ratio->unshade(frame, target_points, target.camera, target.lighting, holes);
    if (appearance_frame) ratio->add_reference(now);
    return ratio->gains(now);
  }

  // The target light's colour now against the appearance frames'
  // (light_colour.hpp) and the shading pattern its SH lighting leaves
  // unexplained (residual_shading.hpp), from the same lit vertices.
  FaceLight target_light(const cv::Mat& frame, const TargetFrame& target, const Positions& target_points,
                         const Positions& target_normals, const cv::Mat& cover) const {
    FaceLight light;
    if (texture.target_vertex_albedo().cols() == 0 || !(options.follow_light_colour || residual)) return light;
    const std::vector<LitVertex> lit = lit_vertices(
        frame, target_points, target_normals,
        cover.empty() ? texture.target_vertex_seen() : uncovered(skin, texture.target_vertex_seen(), cover),
        target.camera, target.lighting);
    if (options.follow_light_colour) light.tint = light_colour(lit, texture.target_vertex_albedo());
    if (residual) light.residual_gains = residual->gains(lit, texture.target_vertex_albedo());
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
    // Across the openings of the skin mesh: up to 6 % of the window each
    // way (the window is about 1.4 face widths: some 12 mm).
    const cv::Mat in_front =
        cover_in_front(skin, target_points, window, out.window.size(), cover, cvRound(0.06 * out.window.width));
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
  const cv::Mat& texture = impl_->texture.texture();
  if (texture.empty()) return {};
  std::vector<cv::Mat> ch;
  cv::split(texture, ch);
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
  const bool appearance_frame = m.texture.target_frames() < m.options.appearance_frames;
  auto t0 = std::chrono::steady_clock::now();
  const Impl::Cover cover = m.covers ? m.find_cover(frame, target, target_points) : Impl::Cover{};
  const double occlusion_ms = m.covers ? ms_since(t0) : 0.0;
  t.occlusion_ms += occlusion_ms;
  t.flow_frames += cover.motion_measured ? 1 : 0;
  t0 = std::chrono::steady_clock::now();
  const cv::Mat ratio_gains =
      m.ratio ? m.expression_gains(frame, target, target_points, holes, cover.skin, appearance_frame) : cv::Mat();
  const double ratio_ms = m.ratio ? ms_since(t0) : 0.0;
  t.ratio_ms += ratio_ms;
  t0 = std::chrono::steady_clock::now();
  if (appearance_frame) m.texture.add_target_frame(frame, target_points, target.camera, target.lighting, holes);
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
      render_swapped_face(m.skin, m.texture.levels(), swapped_points, normals, target.camera, window, out.window.size(),
                          target.lighting, light, m.options.silhouette_fade_start, out.alpha);
  t.render_ms += ms_since(start) - appearance_ms - ratio_ms - occlusion_ms;

  if (m.options.wrinkles && target.hierarchy && target.hierarchy->num_levels() > 1 && target.fine.cols() > 0) {
    t0 = std::chrono::steady_clock::now();
    const double setup_ms = m.wrinkles.shade(*target.hierarchy, target.fine, target.expression, target.lighting,
                                             target_points, swapped_points, window, render);
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
