#include "facecap/pipeline/face_transform_stream.hpp"

#include <chrono>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_reshading.hpp"
#include "facecap/compose/mouth_warp.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/model/eye_look.hpp"
#include "facecap/model/eye_margins.hpp"
#include "facecap/pipeline/cover_preparation.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/swap/skin_texture.hpp"
#include "facecap/swap/weighted_channels.hpp"

namespace facecap {

namespace {

// What covers the face stays in front of the re-rendered one: the layer
// keeps the frame's own pixels where the frame shows a cover over the
// tracked face, and where the new face would show a point of the surface
// that the frame has covered (its colour there is the cover's, and would
// move with the expression). `cover`: FaceCovers::covered's grid.
void keep_covers_in_front(const cv::Mat& frame, const TriangleMesh& skin, const Positions& tracked,
                          const Positions& changed, const PinholeCamera& camera, const cv::Mat& cover,
                          FaceLayer& layer) {
  if (cv::countNonZero(cover > 0) == 0) return;  // most frames: nothing to draw
  // Drawn at half the window's resolution (the covers' edges fade over
  // 2 mm, some 4 px at 720p) and scaled up.
  const PinholeCamera window = camera.cropped(layer.box.x, layer.box.y).resized(0.5);
  const cv::Size half((layer.box.width + 1) / 2, (layer.box.height + 1) / 2);
  // Across the skin's openings (the mouth, the eyes) up to 6 % of the
  // window each way, as the swap (the window is about 1.2 face widths
  // here: some 10 mm).
  const int across = cvRound(0.06 * half.width);
  const cv::Mat in_front_half = cv::max(cover_in_front(skin, tracked, window, half, cover, across),
                                        cover_in_front(skin, changed, window, half, cover, across));
  if (cv::countNonZero(in_front_half > 0) == 0) return;
  cv::Mat in_front;
  cv::resize(in_front_half, in_front, layer.box.size(), 0, 0, cv::INTER_LINEAR);
  cv::Mat colour, own;
  layer.colour.convertTo(colour, CV_32FC3);
  frame(layer.box).convertTo(own, CV_32FC3);
  colour += times_weight(own - colour, in_front);
  colour.convertTo(layer.colour, CV_8UC3);
  layer.mask.setTo(0, in_front > 0.5f);
}

// What the frame shows of eye `e` (0: iBUG 36-41, 1: 42-47): its iris and
// the opening its landmarks mark; none where no iris was found.
std::optional<VisibleEye> visible_eye(const CoarseFit& fit, int e) {
  const std::optional<IrisObservation>& iris = fit.irises[e];
  if (!iris || !(iris->radius > 0)) return std::nullopt;
  VisibleEye eye;
  eye.iris_centre = cv::Point2f(float(iris->centre.x()), float(iris->centre.y()));
  eye.iris_radius = float(iris->radius);
  for (int k = first_eye_landmark(e); k < first_eye_landmark(e) + kEyeLandmarks; ++k)
    eye.opening.emplace_back(fit.observed[k].x(), fit.observed[k].y());
  return eye;
}

// `options` with the gaze's shapes held as tracked (TransformOptions::kept_shapes).
TransformOptions with_gaze_kept(TransformOptions options, const FaceModel& model) {
  for (const int shape : EyeLookShapes(model).indices()) options.kept_shapes.push_back(shape);
  return options;
}

}  // namespace

void TransformTimings::add_stream(const TransformTimings& stream) {
  mapping_ms += stream.mapping_ms;
  lighting_ms += stream.lighting_ms;
  render_ms += stream.render_ms;
  covers_ms += stream.covers_ms;
  cover_preparation_ms += stream.cover_preparation_ms;
  cover_flow_frames += stream.cover_flow_frames;
  edit_thread_cpu_ms += stream.edit_thread_cpu_ms;
  lighting_cpu_ms += stream.lighting_cpu_ms;
  cover_preparation_cpu_ms += stream.cover_preparation_cpu_ms;
}

FaceTransformStream::FaceTransformStream(const FaceModel& model, const ExpressionMapper& mapper,
                                         const TransformOptions& options, const CoverOptions& covers, int width,
                                         int height, Output output)
    : model_(model),
      width_(width),
      height_(height),
      output_(std::move(output)),
      transformer_(mapper, lip_basis(model), with_gaze_kept(options, model)) {
  const TriangleMesh face = model.region_mesh(regions::kFace);
  skin_ = masked_triangles(face.triangles, face_skin_mask());
  for (int i = 60; i < 68; ++i) inner_lips_.push_back(model.landmarks.vertices[i]);
  eye_margins_ = eye_margin_loops(model, skin_);
  // The lighting, the mapping and the re-render run on the refinement stage's
  // thread, concurrently with the next frames' capture (§4.4.1's pipelining);
  // frames reach it and leave it in order, so the results are those of one
  // thread.
  stage_ = std::make_unique<RefineStage>(model, lighting_only_refinement(), [this](const RefinedFrame& r) { take(r); });
  if (covers.keep_occluders) {
    cover_skin_ = skin_mesh(model);
    covers_ = std::make_unique<FaceCovers>(model, cover_skin_, covers, mean_face_mm_per_uv(model, cover_skin_));
    preparation_ = covers_->new_preparation();
    prepare_covers_beside(*stage_, *preparation_);
  }
  // At a cut the smoothing window stops (it does not reach across), and
  // the covers' references start again.
  stage_->on_shot_end([this] {
    emit(transformer_.finish());
    if (covers_) covers_->restart();
    if (shot_end_) shot_end_();
  });
}

FaceTransformStream::~FaceTransformStream() = default;

void FaceTransformStream::push(const CapturedFrame& frame) { stage_->push(frame); }

void FaceTransformStream::finish() {
  stage_->finish();
  emit(transformer_.finish());
  timings_.lighting_ms = stage_->refine_ms();
  timings_.lighting_cpu_ms = stage_->timings().refine_cpu_ms;
  timings_.edit_thread_cpu_ms = stage_->timings().consumer_cpu_ms;
  timings_.cover_preparation_ms = stage_->timings().prepare_ms;
  timings_.cover_preparation_cpu_ms = stage_->timings().prepare_cpu_ms;
}

const Refiner& FaceTransformStream::refiner() const { return stage_->refiner(); }

TransformTimings FaceTransformStream::timings() const { return timings_; }

void FaceTransformStream::take(const RefinedFrame& r) {
  const CapturedFrame& f = r.frame;
  Pending p;
  p.frame = f;
  std::optional<Eigen::VectorXf> weights;
  if (r.refinement) {
    p.coarse = r.coarse;
    p.lighting = r.refinement->lighting;
    p.lighting_final = r.refinement->albedo_final;
    if (const PreparedFrame* prepared = prepared_covers(r)) {
      p.prepared = *prepared;
      timings_.cover_flow_frames += prepared->motion_measured ? 1 : 0;
    }
    weights = f.fit.expression;
  }
  pending_.emplace(f.index, std::move(p));
  const auto t0 = std::chrono::steady_clock::now();
  const auto done = transformer_.push(f.index, f.time, weights);
  timings_.mapping_ms += ms_since(t0);
  emit(done);
}

void FaceTransformStream::emit(const std::vector<TransformedFrame>& done) {
  for (const TransformedFrame& t : done) {
    auto it = pending_.find(t.index);
    if (it == pending_.end()) continue;
    const Pending& p = it->second;
    std::optional<FaceLayer> layer;
    if (t.valid) {
      const auto t0 = std::chrono::steady_clock::now();
      const PinholeCamera cam = PinholeCamera::centered(p.frame.fit.focal, width_, height_);
      const Positions changed =
          to_camera(face_shape_.evaluate(p.frame.identity.identity.cast<float>(), t.weights), p.frame.fit.pose);
      layer = reshade_face(p.frame.image, p.coarse, changed, skin_, p.lighting, cam);
      warp_mouth(p.frame.image, project_vertices(p.coarse, inner_lips_, cam),
                 project_vertices(changed, inner_lips_, cam), *layer);
      for (int e = 0; e < 2; ++e) {
        if (eye_margins_[e].empty()) continue;
        const std::optional<VisibleEye> eye = visible_eye(p.frame.fit, e);
        widen_opening(p.frame.image, project_vertices(p.coarse, eye_margins_[e], cam),
                      project_vertices(changed, eye_margins_[e], cam), *layer, eye ? &*eye : nullptr);
      }
      timings_.render_ms += ms_since(t0);
      if (covers_ && p.prepared) {
        const auto t1 = std::chrono::steady_clock::now();
        const cv::Mat cover = covers_->covered(*p.prepared, p.lighting_final);
        keep_covers_in_front(p.frame.image, covers_->skin(), p.coarse, changed, cam, cover, *layer);
        timings_.covers_ms += ms_since(t1);
      }
    }
    output_({p.frame, t, layer ? &*layer : nullptr});
    ++timings_.frames;
    pending_.erase(it);
  }
}

}  // namespace facecap
