#pragma once
// Shot cuts in a video: the picture's structure changes between two frames
// (an edited interview cutting from one speaker to the other, a clip joined
// to another). Each frame is shrunk to a 64x36 grey thumbnail and compared
// with the last one that had any structure by normalised cross-correlation,
// which a change of exposure or a light (same structure, other levels)
// leaves near 1 and a cut drops near 0. Flat frames (black between shots, a
// fade) neither cut nor become the reference, so a fade out and in is one
// cut, against the last frame before it.
//
// On the five clips of ../shared/data (2,828 frame pairs: a face turning, a
// hand over it, an auto-exposure step) the lowest correlation is 0.86
// (talking_webcam; the others 0.93-1.00); across a join of address_720p_a
// and talking_webcam2 it is 0.08.
#include <opencv2/core.hpp>

namespace facecap {

struct ShotCutOptions {
  // A cut where the correlation with the reference frame falls below this.
  double min_correlation = 0.5;
  // Thumbnails whose grey levels vary less than this (standard deviation)
  // are flat: they say nothing of the shot.
  double min_contrast = 2.0;
};

class ShotCutDetector {
 public:
  explicit ShotCutDetector(ShotCutOptions options = {}) : options_(options) {}

  // Whether this frame (grey, 8-bit; empty: unreadable, not a cut) starts a
  // new shot. The first frame with structure starts none.
  bool next(const cv::Mat& grey);
  // The correlation the last call measured (1 when it had nothing to compare).
  double last_correlation() const { return last_correlation_; }

 private:
  ShotCutOptions options_;
  cv::Mat reference_;  // zero-mean, unit-norm thumbnail of the last frame with structure
  double last_correlation_ = 1.0;
};

}  // namespace facecap
