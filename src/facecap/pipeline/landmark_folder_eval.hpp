#pragma once
// `facecap eval landmarks FOLDER`: a 300-W-style benchmark on a folder of
// annotated images (each IMAGE beside its iBUG annotation, the same name
// with .pts), as LFPW, HELEN, AFW, iBUG and 300-W ship them. Two sets of 68
// points are scored per image:
//  - dlib's, from the detection that overlaps the annotation best
//    (evaluate_landmarks in landmark_eval.hpp);
//  - the fitted model's, projected: the image fitted on its own as a photo,
//    as `track IMAGE` fits it (its own identity and focal length), the face
//    nearest the annotation's centre chosen. This scores the 3D fit as
//    3DDFA-style methods are scored on 2D landmarks.
// Each by the NME of the 300-W convention (mean point error over the
// annotation's outer-eye-corner distance), summarised as the benchmarks do:
// mean, median, the failure rate (NME above 0.08, or no face found) and the
// area under the cumulative error distribution up to 0.08 (AUC_0.08).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "facecap/model/face_model.hpp"

namespace facecap {

// The summary of one set's NMEs; an image whose face was not found counts as
// a failure (and in neither the mean nor the median).
struct LandmarkScores {
  int images = 0;
  int scored = 0;                       // with a face found
  double nme_mean = 0, nme_median = 0;  // of the scored images (the upper middle one of an even count)
  double failure_rate = 0;              // NME > threshold, or none
  double auc = 0;                       // area under the CED curve on [0, threshold], over threshold: 0..1
};

// threshold: 0.08, 300-W's.
LandmarkScores landmark_scores(const std::vector<std::optional<double>>& nmes, double threshold = 0.08);

struct AnnotatedImageScore {
  std::string image;  // file name
  int faces = 0;      // faces dlib found
  std::optional<double> nme, fitted_nme;
  std::string error;  // why a score is missing
};

struct LandmarkFolderEval {
  std::vector<AnnotatedImageScore> images;  // in name order
  LandmarkScores dlib, fitted;
  int unannotated = 0;  // images without a .pts beside them (not scored)
};

// Throws facecap::Error where `folder` is no folder or holds no annotated image.
LandmarkFolderEval evaluate_landmark_folder(const FaceModel& model, const std::filesystem::path& folder,
                                            bool quiet = false);

}  // namespace facecap
