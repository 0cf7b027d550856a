#include "facecap/pipeline/refine_stage.hpp"

#include <chrono>

#include "facecap/pipeline/refine_eval.hpp"

namespace facecap {

RefineStage::RefineStage(const FaceModel& model, const RefineOptions& options, Consumer consumer, int queue_size)
    : model_(model),
      refiner_(make_face_refiner(model, options)),
      consumer_(std::move(consumer)),
      queue_(static_cast<size_t>(queue_size)),
      worker_([this] { run(); }) {}

RefineStage::~RefineStage() {
  queue_.close();
  if (worker_.joinable()) worker_.join();
}

void RefineStage::push(const CapturedFrame& frame) {
  if (error_) std::rethrow_exception(error_);
  if (!queue_.push(frame) && error_) std::rethrow_exception(error_);
}

void RefineStage::finish() {
  queue_.close();
  if (worker_.joinable()) worker_.join();
  if (error_) std::rethrow_exception(error_);
}

void RefineStage::run() {
  try {
    while (std::optional<CapturedFrame> f = queue_.pop()) {
      RefinedFrame out;
      out.frame = std::move(*f);
      out.starts_shot = out.frame.shot != shot_;
      if (out.starts_shot) {
        if (shot_end_) shot_end_();
        refiner_.start_shot();
        shot_ = out.frame.shot;
      }
      if (out.frame.status != TrackStatus::kLost && !out.frame.image.empty()) {
        out.camera = PinholeCamera::centered(out.frame.fit.focal, out.frame.image.cols, out.frame.image.rows);
        out.coarse = to_camera(
            model_.evaluate(out.frame.identity.identity.cast<float>(), out.frame.fit.expression, regions::kFace),
            out.frame.fit.pose);
        const auto t0 = std::chrono::steady_clock::now();
        out.refinement = refiner_.refine(out.frame.image, out.coarse, out.camera);
        refine_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        ++refined_;
      }
      consumer_(out);
    }
  } catch (...) {
    error_ = std::current_exception();
    queue_.close();
  }
}

}  // namespace facecap
