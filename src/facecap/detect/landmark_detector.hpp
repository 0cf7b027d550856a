#pragma once
// dlib's 68-point shape predictor (an ensemble of regression trees trained on
// iBUG 300-W; non-commercial licence, see README).
#include <filesystem>
#include <memory>

#include <opencv2/core.hpp>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

// FACECAP_LANDMARK_MODEL, else /usr/share/dlib/shape_predictor_68_face_landmarks.dat.
std::filesystem::path default_landmark_model_path();

class LandmarkDetector {
 public:
  // Throws facecap::Error naming the file when it is missing or not a shape predictor.
  explicit LandmarkDetector(const std::filesystem::path& model_path = default_landmark_model_path());
  ~LandmarkDetector();
  LandmarkDetector(LandmarkDetector&&) noexcept;
  LandmarkDetector& operator=(LandmarkDetector&&) noexcept;

  // Landmarks of the face in `box` (a box like the HOG detector's) in a grey image.
  Landmarks detect(const cv::Mat& grey, const Box& box) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
