#include "facecap/pipeline/face_transform_stream.hpp"

#include <chrono>

#include "facecap/compose/face_reshading.hpp"
#include "facecap/compose/mouth_warp.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/pipeline/refine_eval.hpp"

namespace facecap {

FaceTransformStream::FaceTransformStream(const FaceModel& model, const ExpressionMapper& mapper,
                                         const TransformOptions& options, int width, int height, Output output)
    : model_(model),
      width_(width),
      height_(height),
      output_(std::move(output)),
      transformer_(mapper, lip_basis(model), options) {
  const TriangleMesh face = model.region_mesh(regions::kFace);
  skin_ = masked_triangles(face.triangles, face_skin_mask());
  for (int i = 60; i < 68; ++i) inner_lips_.push_back(model.landmarks.vertices[i]);
  // The lighting, the mapping and the re-render run on the refinement stage's
  // thread, concurrently with the next frames' capture (§4.4.1's pipelining);
  // frames reach it and leave it in order, so the results are those of one
  // thread.
  stage_ = std::make_unique<RefineStage>(model, lighting_only_refinement(), [this](const RefinedFrame& r) { take(r); });
  // At a cut the smoothing window stops (it does not reach across).
  stage_->on_shot_end([this] {
    emit(transformer_.finish());
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
      timings_.render_ms += ms_since(t0);
    }
    output_({p.frame, t, layer ? &*layer : nullptr});
    ++timings_.frames;
    pending_.erase(it);
  }
}

}  // namespace facecap
