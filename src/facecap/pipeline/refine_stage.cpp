#include "facecap/pipeline/refine_stage.hpp"

#include "facecap/core/cpu_time.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/core/thread_name.hpp"
#include "facecap/pipeline/refine_eval.hpp"

namespace facecap {

RefineStage::RefineStage(const FaceModel& model, const RefineOptions& options, Consumer consumer, int queue_size)
    : face_shape_(model, regions::kFace),
      refiner_(make_face_refiner(model, options)),
      consumer_(std::move(consumer)),
      queue_(static_cast<size_t>(queue_size)),
      handoff_(1),
      refined_frames_(1),
      started_(std::chrono::steady_clock::now()),
      consumer_thread_([this] { run_consumer(); }),
      second_half_([this] { run_second_half(); }),
      first_half_([this] { run_first_half(); }) {}

RefineStage::~RefineStage() {
  fail(nullptr);  // closes the queues and wakes a first thread waiting for the others to drain
  join_all();
}

void RefineStage::join_all() {
  for (std::jthread* t : {&first_half_, &second_half_, &consumer_thread_})
    if (t->joinable()) t->join();
}

void RefineStage::fail(std::exception_ptr error) {
  {
    const std::lock_guard lock(mutex_);
    if (!error_) error_ = error;
    failed_ = true;
  }
  drained_.notify_all();
  queue_.close();
  handoff_.close();
  refined_frames_.close();
}

std::exception_ptr RefineStage::error() const {
  const std::lock_guard lock(mutex_);
  return error_;
}

void RefineStage::push(const CapturedFrame& frame) {
  if (const auto e = error()) std::rethrow_exception(e);
  const auto t0 = std::chrono::steady_clock::now();
  const bool queued = queue_.push(frame);
  push_wait_ms_ += ms_since(t0);
  if (!queued)
    if (const auto e = error()) std::rethrow_exception(e);
}

void RefineStage::finish() {
  queue_.close();
  join_all();
  timings_.refine_ms = first_.refine_ms + second_.refine_ms;
  timings_.coarse_ms = first_.coarse_ms;
  timings_.prepare_ms = second_.prepare_ms;
  timings_.consumer_ms = first_.consumer_ms + third_.consumer_ms;
  timings_.startup_ms = first_.startup_ms;
  timings_.first_refine_ms = first_.first_refine_ms;
  timings_.idle_ms = first_.idle_ms;
  timings_.push_wait_ms = push_wait_ms_;
  timings_.first_to_last_ms = third_.first_to_last_ms;
  timings_.refine_cpu_ms = first_.refine_cpu_ms + second_.refine_cpu_ms;
  timings_.prepare_cpu_ms = second_.prepare_cpu_ms;
  timings_.consumer_cpu_ms = first_.consumer_cpu_ms + third_.consumer_cpu_ms;
  if (const auto e = error()) std::rethrow_exception(e);
}

void RefineStage::wait_until_drained() {
  std::unique_lock lock(mutex_);
  drained_.wait(lock, [&] { return failed_ || finished_ == handed_; });
}

// Each frame's coarse face and the refinement's first half; a shot cut first
// lets the second thread hand on the last shot's frames.
void RefineStage::run_first_half() {
  using Clock = std::chrono::steady_clock;
  name_this_thread("facecap-refine1");
  try {
    refiner_.prepare_devices();  // while capture starts up
    Clock::time_point waiting = Clock::now();
    while (std::optional<CapturedFrame> f = queue_.pop()) {
      if (frames_++ == 0) {
        first_frame_ = Clock::now();
        first_.startup_ms = std::chrono::duration<double, std::milli>(first_frame_ - started_).count();
      } else {
        first_.idle_ms += ms_since(waiting);
      }
      Handoff h;
      RefinedFrame& out = h.frame;
      out.frame = std::move(*f);
      out.starts_shot = out.frame.shot != shot_;
      if (out.starts_shot) {
        wait_until_drained();
        const auto t0 = Clock::now();
        const double cpu0 = thread_cpu_ms();
        if (shot_end_) shot_end_();
        first_.consumer_ms += ms_since(t0);
        first_.consumer_cpu_ms += thread_cpu_ms() - cpu0;
        refiner_.start_shot();
        shot_ = out.frame.shot;
      }
      if (out.frame.status != TrackStatus::kLost && !out.frame.image.empty()) {
        auto t0 = Clock::now();
        out.camera = PinholeCamera::centered(out.frame.fit.focal, out.frame.image.cols, out.frame.image.rows);
        out.coarse =
            to_camera(face_shape_.evaluate(out.frame.identity.identity.cast<float>(), out.frame.fit.expression),
                      out.frame.fit.pose);
        first_.coarse_ms += ms_since(t0);
        t0 = Clock::now();
        const double cpu0 = thread_cpu_ms();
        h.pending = refiner_.begin_frame(out.frame.image, out.coarse, out.camera);
        first_.refine_cpu_ms += thread_cpu_ms() - cpu0;
        const double ms = ms_since(t0);
        first_.refine_ms += ms;
        if (refined_ == 0) first_.first_refine_ms = ms;
        ++refined_;
      }
      {
        const std::lock_guard lock(mutex_);
        ++handed_;
      }
      if (!handoff_.push(std::move(h))) break;  // the second thread failed
      waiting = Clock::now();
    }
    handoff_.close();
  } catch (...) {
    fail(std::current_exception());
  }
}

// The refinement's second half of each frame, in frame order.
void RefineStage::run_second_half() {
  name_this_thread("facecap-refine2");
  try {
    while (std::optional<Handoff> h = handoff_.pop()) {
      RefinedFrame& out = h->frame;
      if (h->pending) {
        const auto t0 = std::chrono::steady_clock::now();
        const double cpu0 = thread_cpu_ms();
        out.refinement = refiner_.finish_frame(std::move(*h->pending));
        second_.refine_ms += ms_since(t0);
        second_.refine_cpu_ms += thread_cpu_ms() - cpu0;
      }
      if (prepare_) {
        const auto t0 = std::chrono::steady_clock::now();
        const double cpu0 = thread_cpu_ms();
        prepare_(out);
        second_.prepare_ms += ms_since(t0);
        second_.prepare_cpu_ms += thread_cpu_ms() - cpu0;
      }
      if (!refined_frames_.push(std::move(out))) break;  // the third thread failed
    }
    refined_frames_.close();
  } catch (...) {
    fail(std::current_exception());
  }
}

// The consumer, on each refined frame in frame order.
void RefineStage::run_consumer() {
  using Clock = std::chrono::steady_clock;
  name_this_thread("facecap-output");
  try {
    while (std::optional<RefinedFrame> out = refined_frames_.pop()) {
      const Clock::time_point t0 = Clock::now();
      const double cpu0 = thread_cpu_ms();
      consumer_(*out);
      const Clock::time_point end = Clock::now();
      third_.consumer_cpu_ms += thread_cpu_ms() - cpu0;
      third_.consumer_ms += std::chrono::duration<double, std::milli>(end - t0).count();
      // first_frame_ was set before the first hand-off, which the queues' locks order before this.
      third_.first_to_last_ms = std::chrono::duration<double, std::milli>(end - first_frame_).count();
      {
        const std::lock_guard lock(mutex_);
        ++finished_;
      }
      drained_.notify_all();
    }
  } catch (...) {
    fail(std::current_exception());
  }
}

}  // namespace facecap
