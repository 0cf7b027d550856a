#include "facecap/pipeline/synth_landmark_eval.hpp"

#include <algorithm>

#include "facecap/core/progress.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/pipeline/landmark_eval.hpp"
#include "facecap/synth/synth_renderer.hpp"

namespace facecap {

SynthLandmarkEval evaluate_synthetic_landmarks(const FaceModel& model, const SynthOptions& options, bool quiet) {
  const SynthPerformance perf = make_performance(model, options);
  const SynthRenderer renderer(model, perf);
  const FaceDetector detector;
  const LandmarkDetector landmarks;
  std::mt19937_64 rng(options.seed);
  SynthLandmarkEval out;
  std::vector<double> nme, nme_inner;
  Progress progress("synthetic landmarks", options.frames, quiet);
  for (const SynthFrame& frame : perf.frames) {
    const cv::Mat image = renderer.render(frame, rng);
    const Landmarks truth = renderer.landmarks(frame);
    ++out.frames;
    const auto faces = detector.detect(image);
    progress.update(out.frames);
    if (faces.empty()) continue;
    ++out.detected;
    const Landmarks lm = landmarks.detect(image, faces.front().box);
    nme.push_back(landmark_nme(lm, truth));
    double inner = 0;
    for (int i = 17; i < kNumLandmarks; ++i) inner += (lm[i] - truth[i]).norm();
    nme_inner.push_back(inner / (kNumLandmarks - 17) / outer_eye_distance(truth));
    out.regions += region_nme(lm, truth);
  }
  if (out.detected > 0) out.regions /= out.detected;
  progress.finish();
  out.detection_rate = out.frames ? double(out.detected) / out.frames : 0.0;
  out.nme_median = median(nme);
  for (double v : nme) out.nme_mean += v / nme.size();
  out.nme_inner_median = median(nme_inner);
  return out;
}

}  // namespace facecap
