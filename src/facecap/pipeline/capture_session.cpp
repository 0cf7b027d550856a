#include "facecap/pipeline/capture_session.hpp"

#include <chrono>

#include "facecap/core/stopwatch.hpp"
#include "facecap/pipeline/face_capture.hpp"
#include "facecap/pipeline/frame_loop.hpp"

namespace facecap {

std::string unreadable_frames_note(const CaptureSummary& summary, const std::string& what) {
  if (summary.unreadable == 0) return "";
  return std::to_string(summary.unreadable) + " frame(s) of " + what +
         " could not be read and are lost (the first: " + summary.first_error + ")";
}

CaptureSummary run_capture(const FaceModel& model, FrameSource& source, CaptureOptions options, const FrameSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  const InputInfo info = source.info();
  if (info.kind == InputKind::kImage) options.fit.set_single_image();
  const LandmarkDetector landmark_detector;
  FaceCapture face(model, landmark_detector, options, info, sink);
  const double setup_ms = ms_since(start);
  const FrameLoopResult loop =
      run_frame_loop(source, options, [&](const DecodedFrame& d, bool cut) { face.push(d, cut); });
  CaptureSummary summary = face.finish();
  summary.cuts = loop.cuts;
  summary.stopped_by_user = loop.stopped_by_user;
  StageTimings& t = summary.timings;
  t.setup_ms = setup_ms;
  t.decode_ms = loop.decode_ms;
  t.frames = loop.frames;
  t.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace facecap
