#include "facecap/pipeline/frame_loop.hpp"

#include <chrono>
#include <cstdio>
#include <exception>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <thread>

#include "facecap/core/bounded_queue.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/core/thread_name.hpp"
#include "facecap/pipeline/capture_session.hpp"

namespace facecap {

FrameLoopResult run_frame_loop(FrameSource& source, const CaptureOptions& options,
                               const std::function<void(const DecodedFrame&, bool cut)>& on_frame) {
  const InputInfo& info = source.info();
  FrameLoopResult result;
  const int remaining = info.frames > 0 ? info.frames - info.frames_past_end - info.first_frame : -1;
  const int total =
      options.max_frames > 0 && (remaining <= 0 || options.max_frames < remaining) ? options.max_frames : remaining;
  Progress progress("capture", total, options.quiet);
  ShotCutDetector cuts(options.shot_cut);
  const bool find_cuts = options.shot_cuts && info.kind != InputKind::kImage;

  BoundedQueue<DecodedFrame> decoded(4);
  std::exception_ptr decode_error;
  // The source's word on how reading went, taken by the decoding thread
  // once it stops and read here once it is joined.
  std::string early_end;
  int refused = 0;
  std::jthread decoder([&] {
    name_this_thread("facecap-decode");
    try {
      for (int n = 0; options.max_frames <= 0 || n < options.max_frames; ++n) {
        DecodedFrame d;
        const auto t0 = std::chrono::steady_clock::now();
        if (!source.read(d.frame)) {
          early_end = source.early_end();
          break;
        }
        if (!d.frame.image.empty()) cv::cvtColor(d.frame.image, d.grey, cv::COLOR_BGR2GRAY);
        d.decode_ms = ms_since(t0);
        if (!decoded.push(std::move(d))) break;
      }
      refused = source.refused_packets();
    } catch (...) {
      decode_error = std::current_exception();
    }
    decoded.close();
  });
  struct CloseOnExit {
    BoundedQueue<DecodedFrame>& q;
    ~CloseOnExit() { q.close(); }  // unblocks the decoder if a stage throws
  } close_on_exit{decoded};

  // A camera has no end of its own: Ctrl-C ends it, and what was captured is
  // kept. Anything else is a job that was stopped: nothing is written.
  const bool live = info.kind == InputKind::kCamera;
  struct LiveInput {
    explicit LiveInput(bool live) { set_interrupt_ends_input(live); }
    ~LiveInput() { set_interrupt_ends_input(false); }
  } live_input{live};
  while (std::optional<DecodedFrame> d = decoded.pop()) {
    if (live && interrupted()) {
      clear_interrupt();
      result.stopped_by_user = true;
      decoded.close();  // the decoder stops at its next frame
      break;
    }
    throw_if_interrupted();
    result.decode_ms += d->decode_ms;
    const bool cut = find_cuts && cuts.next(d->grey);
    result.cuts += cut;
    result.damage.damaged += d->frame.damaged;
    on_frame(*d, cut);
    ++result.frames;
    progress.update(result.frames);
  }
  decoder.join();
  if (decode_error) std::rethrow_exception(decode_error);
  result.damage.early_end = early_end;
  result.damage.refused = refused;
  progress.finish();
  if (result.stopped_by_user && !options.quiet)
    std::fprintf(stderr, "facecap: the camera was stopped (Ctrl-C) after %d frames; they are written\n", result.frames);
  return result;
}

}  // namespace facecap
