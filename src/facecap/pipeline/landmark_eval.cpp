#include "facecap/pipeline/landmark_eval.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/face_tracker.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

namespace {

float range_nme(const Landmarks& e, const Landmarks& t, int from, int to) {
  double s = 0;
  for (int i = from; i <= to; ++i) s += (e[i] - t[i]).norm();
  return float(s / (to - from + 1) / std::max(1e-6f, outer_eye_distance(t)));
}

}  // namespace

RegionNme& RegionNme::operator+=(const RegionNme& o) {
  jaw += o.jaw;
  brows += o.brows;
  nose += o.nose;
  eyes += o.eyes;
  mouth += o.mouth;
  return *this;
}

RegionNme& RegionNme::operator/=(double k) {
  for (double* v : {&jaw, &brows, &nose, &eyes, &mouth}) *v /= k;
  return *this;
}

RegionNme region_nme(const Landmarks& e, const Landmarks& t) {
  RegionNme out;
  out.jaw = range_nme(e, t, 0, 16);
  out.brows = range_nme(e, t, 17, 26);
  out.nose = range_nme(e, t, 27, 35);
  out.eyes = range_nme(e, t, 36, 47);
  out.mouth = range_nme(e, t, 48, 67);
  return out;
}

LandmarkEvalResult evaluate_landmarks(const std::filesystem::path& image_path, const std::filesystem::path& pts) {
  const Landmarks truth = read_pts(pts);
  auto source = open_input(image_path.string());
  if (source->info().kind != InputKind::kImage) throw Error("eval landmarks needs an image: " + image_path.string());
  Frame frame;
  source->read(frame);
  const auto faces = FaceDetector(FaceDetectorOptions{.max_side = 0}).detect(frame.image);
  if (faces.empty()) throw Error("no face found in " + image_path.string());
  const Box truth_box = bounding_box(truth);
  const auto best = std::max_element(faces.begin(), faces.end(), [&](const FaceDetection& a, const FaceDetection& b) {
    return box_overlap(a.box, truth_box) < box_overlap(b.box, truth_box);
  });
  LandmarkEvalResult result;
  result.faces = static_cast<int>(faces.size());
  result.detected = LandmarkDetector().detect(frame.image, best->box);
  const Landmarks& e = result.detected;
  result.nme = landmark_nme(e, truth);
  result.regions = region_nme(e, truth);
  for (int i = 0; i < kNumLandmarks; ++i) {
    const float d = (e[i] - truth[i]).norm();
    result.mean_error_px += d / kNumLandmarks;
    result.max_error_px = std::max(result.max_error_px, d);
  }
  return result;
}

}  // namespace facecap
