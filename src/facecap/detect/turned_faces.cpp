#include "facecap/detect/turned_faces.hpp"

#include <algorithm>

#include "facecap/core/stopwatch.hpp"

namespace facecap {

std::vector<TurnedFace> find_turned_faces(const FaceDetector& detector, const cv::Mat& grey,
                                          std::span<const float> turns, int max_side, double* ms) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<TurnedFace> found;
  const UprightView frame(grey.size(), 0);
  for (const float degrees : turns) {
    const UprightView turned(grey.size(), degrees);
    const int side = std::max(turned.size().width, turned.size().height);
    const float scale = max_side > 0 && side > max_side ? float(max_side) / float(side) : 1.0f;
    for (FaceDetection f : detector.detect(UprightView(grey, degrees, scale).image())) {
      f.box = {f.box.x / scale, f.box.y / scale, f.box.width / scale, f.box.height / scale};
      TurnedFace face{degrees, f, f};
      face.shown.box = carried(f.box, turned, frame);
      const auto same = std::find_if(found.begin(), found.end(),
                                     [&](const TurnedFace& g) { return same_face(face.shown.box, g.shown.box); });
      if (same == found.end()) {
        found.push_back(face);
      } else if (f.score > same->in_view.score) {
        *same = face;
      }
    }
  }
  if (ms != nullptr) *ms += ms_since(t0);
  return found;
}

std::vector<TurnedFace> find_first_turned_faces(const FaceDetector& detector, const cv::Mat& grey,
                                                std::span<const float> turns, int max_side, double* ms) {
  std::vector<TurnedFace> found = find_turned_faces(detector, grey, turns, max_side, ms);
  if (found.empty()) found = find_turned_faces(detector, grey, kFaceHalfTurns, max_side, ms);
  return found;
}

}  // namespace facecap
