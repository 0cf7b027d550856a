#pragma once
// `facecap eval landmarks IMAGE PTS`: dlib's 68 landmarks on an annotated
// image, scored against the annotation.
#include <filesystem>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

// NME per face region (iBUG ranges), each normalised as the whole NME is.
struct RegionNme {
  double jaw = 0, brows = 0, nose = 0, eyes = 0, mouth = 0;

  RegionNme& operator+=(const RegionNme& o);
  RegionNme& operator/=(double k);
};

struct LandmarkEvalResult {
  int faces = 0;  // faces the detector found
  float nme = 0;  // mean error / outer-eye distance of the annotation (300-W convention)
  float mean_error_px = 0;
  float max_error_px = 0;
  RegionNme regions;
  Landmarks detected = zero_landmarks();
};

// The face used is the detection that overlaps the annotation best. Throws
// facecap::Error for unreadable files or when no face is found.
LandmarkEvalResult evaluate_landmarks(const std::filesystem::path& image, const std::filesystem::path& pts);

// Per-region NME of `estimate` against `truth`.
RegionNme region_nme(const Landmarks& estimate, const Landmarks& truth);

}  // namespace facecap
