#pragma once
// The refinement stage of capture (§4.4.1: coarse tracking and refinement
// run concurrently on consecutive frames): it takes tracked frames from a
// bounded queue, refines them, and hands each result, in frame order, to a
// consumer (the track job's writers, a swap). Three threads share the work in
// a pipeline of their own: the first solves a frame's lighting, albedo and
// coarsest level (Refiner::begin_frame) while the second solves the previous
// frame's finer levels (Refiner::finish_frame) and the third runs the
// consumer on the frame before that.
#include <any>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
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
  // What the stage's prepare hook (RefineStage::on_prepare) made of the frame.
  std::any prepared;
};

// Where the stage's threads spend a run, to tell whether capture and
// refinement overlap (all milliseconds, summed over the run).
struct RefineStageTimings {
  double refine_ms = 0;         // the refinement's work: Refiner::begin_frame() and finish_frame()
  double coarse_ms = 0;         // the coarse face in camera space for it
  double prepare_ms = 0;        // the prepare hook (on_prepare)
  double consumer_ms = 0;       // the consumer (writers), shot ends included
  double startup_ms = 0;        // from the stage's start to its first frame: capture's own start-up (identity solve)
  double first_refine_ms = 0;   // the first frame's first half, which builds the mesh hierarchy (in refine_ms too)
  double idle_ms = 0;           // the first thread waiting for frames after the first one
  double push_wait_ms = 0;      // capture's thread blocked in push() on a full queue
  double first_to_last_ms = 0;  // from the first frame's arrival to the last frame's end
  // The CPU time (core/cpu_time.hpp) of refine_ms, prepare_ms and
  // consumer_ms, on the stage's own threads (what they hand the pool, the
  // pool's: pool_cpu_ms()).
  double refine_cpu_ms = 0;
  double prepare_cpu_ms = 0;
  double consumer_cpu_ms = 0;
};

class RefineStage {
 public:
  using Consumer = std::function<void(const RefinedFrame&)>;
  // The consumer runs on the stage's third thread.
  RefineStage(const FaceModel& model, const RefineOptions& options, Consumer consumer, int queue_size = 3);
  ~RefineStage();

  // Runs on the stage's first thread at a shot cut, after the last shot's
  // last frame reached the consumer (the other two threads wait meanwhile) and
  // before the refiner starts its albedo and lighting again: what a consumer
  // keeps per shot (the glTF's albedo) is still the last shot's here. Set it
  // before the first push().
  void on_shot_end(std::function<void()> hook) { shot_end_ = std::move(hook); }

  // Runs on the stage's second thread on each frame, in frame order, after
  // its refinement and before the consumer takes it, beside the consumer's
  // work on the frame before: what a consumer can compute ahead (the swap's
  // unshading and moving covers) goes into RefinedFrame::prepared. Set it
  // before the first push().
  void on_prepare(std::function<void(RefinedFrame&)> hook) { prepare_ = std::move(hook); }

  // Queues a frame (blocks while the queue is full). Rethrows a failure of any of its threads.
  void push(const CapturedFrame& frame);
  // Waits for the queue to drain; rethrows a failure of any of its threads.
  void finish();

  // The refiner's hierarchy may be read at any time once the first frame was
  // refined; the rest of its state from the consumer only at a shot's end,
  // or after finish().
  const Refiner& refiner() const { return refiner_; }
  // These after finish().
  double refine_ms() const { return timings_.refine_ms; }
  int refined_frames() const { return refined_; }
  int frames() const { return frames_; }
  const RefineStageTimings& timings() const { return timings_; }

 private:
  // A frame on its way from the first thread to the second.
  struct Handoff {
    RefinedFrame frame;
    std::optional<PendingFrame> pending;  // empty for lost frames
  };
  void run_first_half();
  void run_second_half();
  void run_consumer();
  void join_all();
  // Blocks the first thread until the consumer has taken every frame handed on.
  void wait_until_drained();
  void fail(std::exception_ptr error);
  std::exception_ptr error() const;

  FaceShapeCache face_shape_;
  Refiner refiner_;
  Consumer consumer_;
  std::function<void()> shot_end_;
  std::function<void(RefinedFrame&)> prepare_;
  BoundedQueue<CapturedFrame> queue_;
  BoundedQueue<Handoff> handoff_;
  BoundedQueue<RefinedFrame> refined_frames_;  // from the second thread to the third
  mutable std::mutex mutex_;                   // error_, handed_, finished_, failed_
  std::condition_variable drained_;
  std::exception_ptr error_;
  int handed_ = 0, finished_ = 0;
  bool failed_ = false;
  // Each thread's own accounting, joined into timings_ by finish().
  RefineStageTimings first_, second_, third_, timings_;
  double push_wait_ms_ = 0;  // push()'s caller's
  std::chrono::steady_clock::time_point started_, first_frame_;
  int refined_ = 0;
  int frames_ = 0;
  int shot_ = 0;                                             // of the last frame (CapturedFrame::shot)
  std::jthread consumer_thread_, second_half_, first_half_;  // last: they start once everything else is made
};

}  // namespace facecap
