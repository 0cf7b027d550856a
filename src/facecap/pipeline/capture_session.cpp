#include "facecap/pipeline/capture_session.hpp"

#include <chrono>
#include <map>

#include "facecap/core/interrupt.hpp"
#include "facecap/core/progress.hpp"

namespace facecap {

namespace {

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

CaptureSummary run_capture(const FaceModel& model, FrameSource& source, CaptureOptions options, const FrameSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  CaptureSummary summary;
  summary.input = source.info();
  if (summary.input.kind == InputKind::kImage) {
    options.fit.still = true;
    options.fit.init_frames = 1;
  }
  const LandmarkDetector landmark_detector;
  FaceTracker face_tracker(landmark_detector, options.tracker);
  CoarseTracker tracker(model, options.fit, summary.input.width, summary.input.height);

  struct Waiting {
    TrackStatus status;
    cv::Mat image;
  };
  std::map<int, Waiting> waiting;  // frames whose fit is not final yet
  auto deliver = [&](const std::vector<CoarseFit>& fits) {
    for (const CoarseFit& fit : fits) {
      auto it = waiting.find(fit.index);
      CapturedFrame out;
      out.index = fit.index;
      out.time = fit.time;
      out.fit = fit;
      out.status = fit.valid ? it->second.status : TrackStatus::kLost;
      out.image = it->second.image;
      waiting.erase(it);
      summary.lost += out.status == TrackStatus::kLost;
      summary.redetected += out.status == TrackStatus::kRedetected;
      ++summary.frames;
      sink(out);
    }
  };

  const int total = options.max_frames > 0 && (summary.input.frames <= 0 || options.max_frames < summary.input.frames)
                        ? options.max_frames
                        : summary.input.frames;
  Progress progress("capture", total, options.quiet);
  StageTimings& t = summary.timings;
  Frame frame;
  for (;;) {
    throw_if_interrupted();
    if (options.max_frames > 0 && t.frames >= options.max_frames) break;
    auto t0 = std::chrono::steady_clock::now();
    if (!source.read(frame)) break;
    t.decode_ms += ms_since(t0);

    t0 = std::chrono::steady_clock::now();
    TrackedFace face;
    if (!frame.image.empty()) face = face_tracker.next(frame.image);
    t.landmarks_ms += ms_since(t0);

    waiting[frame.index] = {face.status, options.keep_images ? frame.image : cv::Mat()};
    std::optional<Landmarks> landmarks;
    if (face.status != TrackStatus::kLost) landmarks = face.landmarks;

    t0 = std::chrono::steady_clock::now();
    const std::vector<CoarseFit> fits = tracker.push(frame.index, frame.time, landmarks);
    t.fit_ms += ms_since(t0);
    // A fit that rejects the landmarks means the box tracker followed
    // something that is not the face: detect afresh on the next frame.
    for (const CoarseFit& fit : fits) {
      if (!fit.valid && fit.index == frame.index) face_tracker.reset();
    }
    deliver(fits);
    ++t.frames;
    progress.update(t.frames);
  }
  const auto t0 = std::chrono::steady_clock::now();
  deliver(tracker.finish());
  t.fit_ms += ms_since(t0);
  progress.finish();
  summary.identity = tracker.identity();
  t.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace facecap
