#pragma once
// How well dlib sees the synthetic renders: the share of frames where the
// HOG detector finds the face, and the landmark NME against the truth.
#include "facecap/pipeline/landmark_eval.hpp"
#include "facecap/synth/performance.hpp"

namespace facecap {

struct SynthLandmarkEval {
  int frames = 0;
  int detected = 0;           // frames where the detector found the face
  double detection_rate = 0;  // detected / frames
  double nme_median = 0;      // against the silhouette-aware truth landmarks
  double nme_mean = 0;
  double nme_inner_median = 0;  // landmarks 17-67 only (no jaw)
  // Per-region NME (iBUG ranges), mean over the detected frames: comparable
  // with `eval landmarks IMAGE PTS` on an annotated photo.
  RegionNme regions;
};

SynthLandmarkEval evaluate_synthetic_landmarks(const FaceModel& model, const SynthOptions& options, bool quiet = false);

}  // namespace facecap
