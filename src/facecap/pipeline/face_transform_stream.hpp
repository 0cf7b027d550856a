#pragma once
// One face's expression transformation through an input, frame by frame
// (chapter 5): the frame's lighting on a refinement stage of its own (only
// the lighting: the source frame carries the fine detail), the weights
// mapped, smoothed and lip-corrected (ExpressionTransformer, k frames of
// delay), and the face re-rendered with them as a layer over the frame: the
// skin re-shaded under the frame's lighting, the source mouth interior warped
// to the new lips, and what covers the face (a hand, a microphone) kept in
// front of it as a swap keeps it (face_covers.hpp). run_transform drives one
// stream; transform --all-faces one per face, their layers composited over
// the same frames.
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "facecap/compose/face_layer.hpp"
#include "facecap/expr/expression_transform.hpp"
#include "facecap/model/face_shape_cache.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/job_cpu.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/swap/face_covers.hpp"

namespace facecap {

struct TransformedFaceFrame {
  const CapturedFrame& frame;        // the source frame, with its image
  const TransformedFrame& weights;   // valid where the face was transformed
  const FaceLayer* layer = nullptr;  // the re-rendered face, to composite over the frame (null where not valid)
};

struct TransformTimings {
  double mapping_ms = 0;  // mapping, smoothing and lip QP
  double lighting_ms = 0;
  double render_ms = 0;             // re-shading, mouth warp and blending
  double covers_ms = 0;             // what covers the face, on the edit's thread (CoverOptions::keep_occluders)
  double cover_preparation_ms = 0;  // the covers' unshading and motion, on the stage's second thread
  int cover_flow_frames = 0;        // frames whose moving covers ran their optical flow (colour_change.hpp)
  int frames = 0;
  // CPU time (core/cpu_time.hpp), for a benchmark's budget of the cores:
  // the edit's thread (mapping, re-render, composite and the frame's
  // writing), the lighting's and the covers' preparation, the stage's own
  // threads; and the job's (the encoder's, the pool's, facecap's whole).
  double edit_thread_cpu_ms = 0;
  double lighting_cpu_ms = 0;
  double cover_preparation_cpu_ms = 0;
  JobCpu job_cpu;

  // Adds a stream's stage times (all but frames and job_cpu, the job's).
  void add_stream(const TransformTimings& stream);
};

class FaceTransformStream {
 public:
  // Called on the stream's own thread, frames in order, each once.
  using Output = std::function<void(const TransformedFaceFrame&)>;
  // `width` x `height`: the input's frames. The mapper is shared (it is thread-safe).
  FaceTransformStream(const FaceModel& model, const ExpressionMapper& mapper, const TransformOptions& options,
                      const CoverOptions& covers, int width, int height, Output output);
  ~FaceTransformStream();
  FaceTransformStream(const FaceTransformStream&) = delete;
  FaceTransformStream& operator=(const FaceTransformStream&) = delete;

  // Runs on the stream's thread at a shot cut, after the shot's last frame
  // left and while the refiner still holds the shot's albedo. Set it before
  // the first push().
  void on_shot_end(std::function<void()> hook) { shot_end_ = std::move(hook); }

  // One tracked frame, with its image (CaptureOptions::keep_images); blocks
  // while the stream's queue is full. Rethrows a failure of the stream.
  void push(const CapturedFrame& frame);
  // The frames still waiting leave; rethrows a failure of the stream.
  void finish();

  const Refiner& refiner() const;
  // After finish(): the stream's stages, summed (frames: those that left).
  TransformTimings timings() const;

 private:
  // A tracked frame waiting for its transformed weights.
  struct Pending {
    CapturedFrame frame;
    Positions coarse;  // camera-space face region, source expression
    ShCoeffs lighting;
    bool lighting_final = false;            // Refinement::albedo_final
    std::optional<PreparedFrame> prepared;  // with covers_
  };
  void take(const RefinedFrame& refined);
  void emit(const std::vector<TransformedFrame>& done);

  const FaceModel& model_;
  FaceShapeCache face_shape_{model_, regions::kFace};  // used on the stage's thread
  int width_, height_;
  Output output_;
  ExpressionTransformer transformer_;
  std::vector<Triangle> skin_;  // the face region's skin triangles, re-shaded
  std::vector<int> inner_lips_;
  std::array<std::vector<int>, 2> eye_margins_;    // the skin's openings at eyes 0 and 1 (eye_margins.hpp)
  TriangleMesh cover_skin_;                        // skin_mesh, with covers_
  std::unique_ptr<FaceCovers> covers_;             // CoverOptions::keep_occluders; used on the stage's thread
  std::unique_ptr<FramePreparation> preparation_;  // with covers_, on the stage's second thread
  std::map<int, Pending> pending_;
  std::function<void()> shot_end_;
  TransformTimings timings_;
  std::unique_ptr<RefineStage> stage_;  // last: its thread ends before what it uses goes
};

}  // namespace facecap
