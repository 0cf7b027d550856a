#include "facecap/pipeline/refine_stage.hpp"

#include "facecap/core/stopwatch.hpp"
#include "facecap/pipeline/refine_eval.hpp"

namespace facecap {

RefineStage::RefineStage(const FaceModel& model, const RefineOptions& options, Consumer consumer, int queue_size)
    : face_shape_(model, regions::kFace),
      refiner_(make_face_refiner(model, options)),
      consumer_(std::move(consumer)),
      queue_(static_cast<size_t>(queue_size)),
      started_(std::chrono::steady_clock::now()),
      worker_([this] { run(); }) {}

RefineStage::~RefineStage() {
  queue_.close();
  if (worker_.joinable()) worker_.join();
}

void RefineStage::push(const CapturedFrame& frame) {
  if (error_) std::rethrow_exception(error_);
  const auto t0 = std::chrono::steady_clock::now();
  const bool queued = queue_.push(frame);
  timings_.push_wait_ms += ms_since(t0);
  if (!queued && error_) std::rethrow_exception(error_);
}

void RefineStage::finish() {
  queue_.close();
  if (worker_.joinable()) worker_.join();
  if (error_) std::rethrow_exception(error_);
}

void RefineStage::run() {
  using Clock = std::chrono::steady_clock;
  try {
    Clock::time_point first, waiting = Clock::now();
    while (std::optional<CapturedFrame> f = queue_.pop()) {
      if (frames_++ == 0) {
        first = Clock::now();
        timings_.startup_ms = std::chrono::duration<double, std::milli>(first - started_).count();
      } else {
        timings_.idle_ms += ms_since(waiting);
      }
      RefinedFrame out;
      out.frame = std::move(*f);
      out.starts_shot = out.frame.shot != shot_;
      if (out.starts_shot) {
        const auto t0 = Clock::now();
        if (shot_end_) shot_end_();
        timings_.consumer_ms += ms_since(t0);
        refiner_.start_shot();
        shot_ = out.frame.shot;
      }
      Clock::time_point t0;
      if (out.frame.status != TrackStatus::kLost && !out.frame.image.empty()) {
        t0 = Clock::now();
        out.camera = PinholeCamera::centered(out.frame.fit.focal, out.frame.image.cols, out.frame.image.rows);
        out.coarse =
            to_camera(face_shape_.evaluate(out.frame.identity.identity.cast<float>(), out.frame.fit.expression),
                      out.frame.fit.pose);
        timings_.coarse_ms += ms_since(t0);
        t0 = Clock::now();
        out.refinement = refiner_.refine(out.frame.image, out.coarse, out.camera);
        timings_.refine_ms += ms_since(t0);
        ++refined_;
      }
      t0 = Clock::now();
      consumer_(out);
      timings_.consumer_ms += ms_since(t0);
      waiting = Clock::now();
      timings_.first_to_last_ms = std::chrono::duration<double, std::milli>(waiting - first).count();
    }
  } catch (...) {
    error_ = std::current_exception();
    queue_.close();
  }
}

}  // namespace facecap
