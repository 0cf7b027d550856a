#pragma once
// `facecap eval landmarks IMAGE PTS`: dlib's 68 landmarks on an annotated
// image, scored against the annotation.
#include <filesystem>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

struct LandmarkEvalResult {
  int faces = 0;  // faces the detector found
  float nme = 0;  // mean error / outer-eye distance of the annotation (300-W convention)
  float mean_error_px = 0;
  float max_error_px = 0;
  float nme_jaw = 0, nme_brows = 0, nme_nose = 0, nme_eyes = 0, nme_mouth = 0;
  Landmarks detected{};
};

// The face used is the detection that overlaps the annotation best. Throws
// facecap::Error for unreadable files or when no face is found.
LandmarkEvalResult evaluate_landmarks(const std::filesystem::path& image, const std::filesystem::path& pts);

// Per-region NME of `estimate` against `truth` (iBUG ranges).
void region_nme(const Landmarks& estimate, const Landmarks& truth, LandmarkEvalResult& out);

}  // namespace facecap
