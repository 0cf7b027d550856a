#pragma once
// The frame loop every capture shares: decoding (and the grey image the
// landmarks need) on its own thread a few frames ahead, shot cuts, Ctrl-C
// (which ends a camera and stops anything else), and the progress bar.
#include <functional>
#include <string>

#include <opencv2/core.hpp>

#include "facecap/io/input.hpp"
#include "facecap/io/input_damage.hpp"

namespace facecap {

struct CaptureOptions;

struct DecodedFrame {
  Frame frame;
  cv::Mat grey;  // empty where the frame could not be read
  double decode_ms = 0;
};

struct FrameLoopResult {
  int frames = 0;
  double decode_ms = 0;  // on the decode thread, summed
  int cuts = 0;
  InputDamage damage;            // what a corrupt input cost the frames read
  bool stopped_by_user = false;  // a camera ended by Ctrl-C
};

// Calls on_frame(frame, cut) for each frame of `source` in order (up to
// options.max_frames), `cut` where a shot cut (options.shot_cuts) falls just
// before it. A camera's Ctrl-C ends the loop (stopped_by_user); anything
// else's throws Interrupted. Rethrows what the decoder or on_frame threw.
FrameLoopResult run_frame_loop(FrameSource& source, const CaptureOptions& options,
                               const std::function<void(const DecodedFrame&, bool cut)>& on_frame);

}  // namespace facecap
