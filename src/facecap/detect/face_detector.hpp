#pragma once
// Frontal face detection with dlib's HOG + linear SVM detector, run on a
// downscaled grey image for speed.
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

struct FaceDetectorOptions {
  // The image is downscaled so that its longer side is at most this many
  // pixels before detection (dlib's detector finds faces of 80 px and up, so
  // 640 finds faces down to about 1/8 of the frame). 0 = never downscale.
  int max_side = 640;
  // A smaller image (or region) is upscaled so that its longer side is this
  // many pixels, for faces below the detector's 80 px window. 0 = never upscale.
  int min_side = 0;
  // Then doubles the searched size this many times (each halves the smallest
  // face found, at about 4 times the time); one resize in all.
  int upsample = 0;
  // Detection score threshold offset (dlib's adjust_threshold; lower finds more).
  double adjust_threshold = 0.0;
};

// The same search at twice the size: faces down to half as small, at about
// 4 times the time. FaceTracker falls back on it where the whole frame holds
// no face at the first size.
inline FaceDetectorOptions twice_the_size(FaceDetectorOptions options) {
  ++options.upsample;
  return options;
}

struct FaceDetection {
  Box box;  // in full-image pixels
  double score = 0.0;
};

// Whether `box` (a detection) is of the face in `face` (a detection's or a
// landmark box): its centre within a quarter of the face's width plus height,
// about half the face's size, of the face's centre.
inline bool same_face(const Box& box, const Box& face) {
  return (box.center() - face.center()).norm() < 0.25f * (face.width + face.height);
}

class FaceDetector {
 public:
  explicit FaceDetector(FaceDetectorOptions options = {});
  ~FaceDetector();
  FaceDetector(FaceDetector&&) noexcept;
  FaceDetector& operator=(FaceDetector&&) noexcept;

  // Faces in a BGR or grey image, largest first.
  std::vector<FaceDetection> detect(const cv::Mat& image) const;
  // Faces within `region` of the image only (the region is clipped to the image).
  std::vector<FaceDetection> detect_in(const cv::Mat& image, const Box& region) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  FaceDetectorOptions options_;
};

}  // namespace facecap
