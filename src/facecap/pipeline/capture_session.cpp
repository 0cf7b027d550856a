#include "facecap/pipeline/capture_session.hpp"

#include <chrono>
#include <cmath>

#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/pipeline/face_capture.hpp"
#include "facecap/pipeline/frame_loop.hpp"

namespace facecap {

std::string unreadable_frames_note(const CaptureSummary& summary, const std::string& what) {
  if (summary.unreadable == 0) return "";
  return std::to_string(summary.unreadable) + " frame(s) of " + what +
         " could not be read and are lost (the first: " + summary.first_error + ")";
}

std::string damaged_input_note(const CaptureSummary& summary, const std::string& what) {
  return joined_notes({unreadable_frames_note(summary, what), input_damage_note(summary.damage, what)});
}

std::string no_face_error(const std::string& what, const InputDamage& damage, const std::string& consequence) {
  return joined_notes({"no face found in any frame of " + what + ": " + consequence, input_damage_note(damage, "it")});
}

void CaptureOptions::check() const {
  fit.check();
  // The command line refuses these by name too (apps/facecap/common.cpp);
  // here they reach library callers, for whom a negative count would
  // otherwise read the whole input.
  if (max_frames < 0)
    throw Error("--max-frames must be 0 (the whole input) or more, not " + std::to_string(max_frames));
  if (!(std::isfinite(start_seconds) && start_seconds >= 0)) throw Error("--start must be 0 or more seconds");
  if (!(shot_cut.min_correlation <= 1)) throw Error("capture option shot_cut.min_correlation must be at most 1");
  if (!(shot_cut.min_contrast >= 0)) throw Error("capture option shot_cut.min_contrast must be 0 or more");
}

CaptureSummary run_capture(const FaceModel& model, FrameSource& source, CaptureOptions options, const FrameSink& sink) {
  options.check();
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
  summary.damage = loop.damage;
  summary.stopped_by_user = loop.stopped_by_user;
  StageTimings& t = summary.timings;
  t.setup_ms = setup_ms;
  t.decode_ms = loop.decode_ms;
  t.frames = loop.frames;
  t.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace facecap
