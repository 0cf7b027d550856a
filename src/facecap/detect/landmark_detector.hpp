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

  // Landmarks of the face in `box` (a box like the HOG detector's) in a grey
  // image: the mean of detect_once on the image and, mirrored back, on its
  // mirror image (test-time flipping). The cascade's errors on a face and on
  // its mirror image are partly its own, so their mean lies nearer the face:
  // on lfpw_image_0010.png NME 0.0257 -> 0.0248, on synthetic renders (seeds
  // 1-4, 60 frames) median NME 3-6 % lower on every seed, and on real footage
  // the points' frame-to-frame jitter 15-17 % lower, for twice the cascade's
  // time (about 2.3 ms more a frame at 1280x720).
  Landmarks detect(const cv::Mat& grey, const Box& box) const;
  // dlib's cascade once, as its shape_predictor finds them (without its
  // rounding to whole pixels).
  Landmarks detect_once(const cv::Mat& grey, const Box& box) const;
  // detect() from detect_once's points on the same box: the mirror pass
  // alone, averaged with them.
  Landmarks average_with_mirror(const cv::Mat& grey, const Box& box, const Landmarks& once) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
