#pragma once
// Whether anything on the face changed colour since the last frame: the
// gate in front of MovingCover's optical flow, the covers' largest cost.
//
// The face unshaded onto its texel grid (face_texture.hpp) holds each
// surface point's own colour wherever the tracked face moves: between two
// frames it changes where the tracking slips (at the features' edges,
// a texel or two wide) and where something moves across the face. A hand
// that moves far enough for MovingCover to find it (6 mm in a frame over
// 8 mm) brings its own colours, its edge and its shadow onto texels that
// held skin, lips or brows, over a patch several millimetres across. Where
// no patch of min_extent_mm changed by min_log_change in some channel, no
// new cover has come, and the flow can be skipped.
//
// Measured on the clips of ../shared/data (2026-12-02, 300 frames each):
// on every frame of emotions_pexels where the flow found a new cover
// (25, her hands coming up to her face), at least 305 texels changed by
// 0.2 past the opening, 24 by 0.3; on the talking heads the gate opens on
// 10-21 % of the frames.
#include <opencv2/core.hpp>

#include "facecap/core/frame_sequence.hpp"
#include "facecap/swap/face_texture.hpp"

namespace facecap {

struct ColourChangeOptions {
  float min_log_change = 0.2f;  // in a channel's log colour (about 22 %)
  float min_extent_mm = 4.0f;   // the patch's width: narrower changes are the tracking's slips
  float min_weight = 0.3f;      // how squarely both frames saw a texel (FaceTexture::weight) for it to count
};

class ColourChange {
 public:
  // `texels_per_mm`: the grid's (MillimetreGrid).
  explicit ColourChange(double texels_per_mm, ColourChangeOptions options = {});

  // Whether `seen` (this frame's face, unshade_face's) changed since
  // the last frame given, frames in order. True where that is unknown: the
  // first frame, after reset(), where `frame_index` does not follow the
  // last frame's (-1: unknown, taken to follow) or the grid's size changed.
  bool changed(const FaceTexture& seen, int frame_index = -1);

  // Forget the last frame.
  void reset();

 private:
  ColourChangeOptions options_;
  int radius_;        // of the opening's disc, texels
  cv::Mat last_log_;  // the last frame's log colour (CV_32FC3)
  cv::Mat last_weight_;
  FrameSequence sequence_;
};

}  // namespace facecap
