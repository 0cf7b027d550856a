#pragma once
// The refinement stage of capture (§4.4.1: coarse tracking and refinement
// run concurrently on consecutive frames): a worker thread that takes
// tracked frames from a bounded queue, refines them, and hands each result,
// in frame order, to a consumer (the track job's writers).
#include <functional>
#include <memory>
#include <thread>

#include "facecap/core/bounded_queue.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/refine/refiner.hpp"

namespace facecap {

struct RefinedFrame {
  CapturedFrame frame;
  std::optional<Refinement> refinement;  // empty for lost frames
  PinholeCamera camera;
  Positions coarse;  // camera-space coarse face (tracked frames)
  // The first frame of a shot after a cut (CapturedFrame::shot): the refiner
  // started its albedo and lighting again here, and so should a consumer
  // whatever it learns across frames.
  bool starts_shot = false;
};

class RefineStage {
 public:
  using Consumer = std::function<void(const RefinedFrame&)>;
  // The consumer runs on the stage's thread.
  RefineStage(const FaceModel& model, const RefineOptions& options, Consumer consumer, int queue_size = 3);
  ~RefineStage();

  // Runs on the stage's thread at a shot cut, after the last shot's last
  // frame reached the consumer and before the refiner starts its albedo and
  // lighting again: what a consumer keeps per shot (the glTF's albedo) is
  // still the last shot's here. Set it before the first push().
  void on_shot_end(std::function<void()> hook) { shot_end_ = std::move(hook); }

  // Queues a frame (blocks while the queue is full). Rethrows a failure of the worker.
  void push(const CapturedFrame& frame);
  // Waits for the queue to drain; rethrows a failure of the worker.
  void finish();

  const Refiner& refiner() const { return refiner_; }
  double refine_ms() const { return refine_ms_; }
  int refined_frames() const { return refined_; }

 private:
  void run();

  const FaceModel& model_;
  Refiner refiner_;
  Consumer consumer_;
  std::function<void()> shot_end_;
  BoundedQueue<CapturedFrame> queue_;
  std::exception_ptr error_;
  double refine_ms_ = 0;
  int refined_ = 0;
  int shot_ = 0;  // of the last frame (CapturedFrame::shot)
  std::jthread worker_;
};

}  // namespace facecap
