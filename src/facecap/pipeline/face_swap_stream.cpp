#include "facecap/pipeline/face_swap_stream.hpp"

#include "facecap/pipeline/cover_preparation.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/swap/frame_preparation.hpp"

namespace facecap {

namespace {

// The target's albedo from its first 4 frames in a row (not every 3rd):
// the appearance waits for it (TargetFrame::lighting_final), and the
// lighting of the frames before it is on another scale. Self-swap
// (`eval swap --self`) median / mean on address_720p_a / _b: 4.325 / 6.210,
// 6.325 / 9.528 with neither; 4.325 / 6.160, 6.325 / 9.514 waiting for the
// albedo of every 3rd frame; 4.325 / 6.100, 6.325 / 9.502 with both.
RefineOptions target_refinement(const SwapOptions& options) {
  RefineOptions refine = lighting_only_refinement();
  refine.albedo.interval = 1;
  // With wrinkles the target is refined as `track --refine` does, on a
  // two-level hierarchy (the coarse mesh and one 4-8 level, about 4x the
  // vertices), whose finest level carries the coating transfer.
  if (options.wrinkles) {
    refine.displacements = true;
    refine.hierarchy.levels = 2;
  }
  return refine;
}

}  // namespace

FaceSwapStream::FaceSwapStream(const FaceModel& model, const cv::Mat& photo, const SourceFace& source,
                               const SwapOptions& options, Output output)
    : model_(model),
      photo_(photo),
      source_(source),
      options_(options),
      output_(std::move(output)),
      swapper_(model, photo, source, options) {
  // The target's lighting, the swap and the output run on the refinement
  // stage's thread, concurrently with the next frames' capture (§4.4.1's
  // pipelining); frames reach it and leave it in order, so the results are
  // those of one thread.
  stage_ = std::make_unique<RefineStage>(model, target_refinement(options), [this](const RefinedFrame& r) { take(r); });
  // Each frame's unshading onto the occlusion grid and its moving covers
  // (frame_preparation.hpp), on the stage's second thread beside the swap
  // of the frame before: the swap's thread is the pipeline's slowest, and
  // these need only the frame, the tracked face and its lighting.
  preparation_ = swapper_.make_preparation();
  if (preparation_) prepare_covers_beside(*stage_, *preparation_);
}

FaceSwapStream::~FaceSwapStream() = default;

void FaceSwapStream::push(const CapturedFrame& frame) { stage_->push(frame); }

void FaceSwapStream::finish() { stage_->finish(); }

const RefineStageTimings& FaceSwapStream::stage_timings() const { return stage_->timings(); }

void FaceSwapStream::take(const RefinedFrame& r) {
  const CapturedFrame& f = r.frame;
  if (r.starts_shot) {
    // A shot cut: what the swapper learnt of the target's first frames
    // (appearance, light colour, expression reference) is of the last shot.
    if (shot_end_) shot_end_();
    swapper_ = FaceSwapper(model_, photo_, source_, options_);
  }
  if (!r.refinement) {
    output_(f, nullptr);
    return;
  }
  TargetFrame t;
  t.identity = f.identity.identity.cast<float>();
  t.expression = f.fit.expression;
  t.pose = f.fit.pose;
  t.camera = r.camera;
  t.lighting = r.refinement->lighting;
  t.lighting_final = r.refinement->albedo_final;
  t.index = f.index;
  t.prepared = prepared_covers(r);
  t.points = &r.coarse;
  if (options_.wrinkles) {
    t.fine = r.refinement->positions;
    t.hierarchy = &stage_->refiner().hierarchy();
  }
  const SwappedFrame result = swapper_.swap(f.image, t, &timings_);
  ++swapped_;
  output_(f, &result);
}

}  // namespace facecap
