#pragma once
// The refinement stage of capture (§4.4.1: coarse tracking and refinement
// run concurrently on consecutive frames): a worker thread that takes
// tracked frames from a bounded queue, refines them, and hands each result,
// in frame order, to a consumer (the track job's writers).
#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "facecap/core/bounded_queue.hpp"
#include "facecap/model/face_shape_cache.hpp"
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

// Where the stage's thread spends a run, to tell whether capture and
// refinement overlap (all milliseconds, summed over the run).
struct RefineStageTimings {
  double refine_ms = 0;         // Refiner::refine()
  double coarse_ms = 0;         // the coarse face in camera space for it
  double consumer_ms = 0;       // the consumer (writers), shot ends included
  double startup_ms = 0;        // from the stage's start to its first frame: capture's own start-up (identity solve)
  double idle_ms = 0;           // waiting for frames after the first one
  double push_wait_ms = 0;      // capture's thread blocked in push() on a full queue
  double first_to_last_ms = 0;  // from the first frame's arrival to the last frame's end
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
  double refine_ms() const { return timings_.refine_ms; }
  int refined_frames() const { return refined_; }
  int frames() const { return frames_; }
  // Complete after finish().
  const RefineStageTimings& timings() const { return timings_; }

 private:
  void run();

  FaceShapeCache face_shape_;
  Refiner refiner_;
  Consumer consumer_;
  std::function<void()> shot_end_;
  BoundedQueue<CapturedFrame> queue_;
  std::exception_ptr error_;
  RefineStageTimings timings_;  // push_wait_ms written by push()'s caller, the rest by the stage's thread
  std::chrono::steady_clock::time_point started_;
  int refined_ = 0;
  int frames_ = 0;
  int shot_ = 0;  // of the last frame (CapturedFrame::shot)
  std::jthread worker_;
};

}  // namespace facecap
