#pragma once
// One target face's swap through an input, frame by frame (chapter 6): the
// target's lighting (and with wrinkles its refinement) on a refinement stage
// of its own (§4.4.1's pipelining), then the source's face rendered into the
// frame by a FaceSwapper that learns this target's appearance; at a shot cut
// the swapper starts again. run_swap drives one stream; swap --all-faces one
// per target face, their changes laid over the same frames.
#include <functional>
#include <memory>

#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/swap/face_swapper.hpp"
#include "facecap/swap/frame_preparation.hpp"

namespace facecap {

class FaceSwapStream {
 public:
  // Called on the stream's own thread, frames in order, each once; `swapped`
  // is null where the face was lost (the frame passes through).
  using Output = std::function<void(const CapturedFrame& frame, const SwappedFrame* swapped)>;
  // `photo` and `source`: the source's reconstruction (swap_job.hpp), shared.
  FaceSwapStream(const FaceModel& model, const cv::Mat& photo, const SourceFace& source, const SwapOptions& options,
                 Output output);
  ~FaceSwapStream();
  FaceSwapStream(const FaceSwapStream&) = delete;
  FaceSwapStream& operator=(const FaceSwapStream&) = delete;

  // Runs on the stream's thread at a shot cut, before the swapper starts
  // again: what it learnt of the last shot (its texture, its size match) is
  // still there. Set it before the first push().
  void on_shot_end(std::function<void()> hook) { shot_end_ = std::move(hook); }

  // One tracked frame with its image (CaptureOptions::keep_images); blocks
  // while the stream's queue is full. Rethrows a failure of the stream.
  void push(const CapturedFrame& frame);
  // The frames still queued are swapped; rethrows a failure of the stream.
  void finish();

  const FaceSwapper& swapper() const { return swapper_; }
  // After finish(): the swap's stages summed, its stage's, and the frames swapped.
  const SwapTimings& timings() const { return timings_; }
  // Its stage's threads' wall and CPU times: the lighting (refine_*), the
  // frames' preparation (prepare_*, frame_preparation.hpp) and the swap (consumer_*).
  const RefineStageTimings& stage_timings() const;
  int swapped() const { return swapped_; }

 private:
  void take(const RefinedFrame& refined);

  const FaceModel& model_;
  const cv::Mat& photo_;
  const SourceFace& source_;
  SwapOptions options_;
  Output output_;
  FaceSwapper swapper_;
  std::unique_ptr<FramePreparation> preparation_;  // used on the stage's second thread only
  std::function<void()> shot_end_;
  SwapTimings timings_;
  int swapped_ = 0;
  std::unique_ptr<RefineStage> stage_;  // last: its thread ends before what it uses goes
};

}  // namespace facecap
