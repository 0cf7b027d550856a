#include "facecap/pipeline/demo.hpp"

#include <algorithm>
#include <memory>
#include <optional>

#include "facecap/core/progress.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/detect/face_tracker.hpp"
#include "facecap/io/input.hpp"
#include "facecap/synth/synthesize.hpp"

namespace facecap {

nlohmann::json run_demo(const FaceModel& model, const DemoOptions& options) {
  std::optional<TempDir> temp;
  std::filesystem::path dir = options.keep_dir;
  if (dir.empty()) {
    temp.emplace("facecap-demo");
    dir = temp->path();
  }
  SynthOptions so;
  so.frames = options.frames;
  so.seed = options.seed;
  const SynthJobResult synth = synthesize(model, so, dir, options.quiet);

  // Capture: landmarks per frame.
  const LandmarkDetector landmark_detector;
  FaceTracker tracker(landmark_detector);
  auto source = open_input(synth.video.string());
  Frame frame;
  int tracked = 0, redetected = 0, lost = 0;
  std::vector<double> nme;
  Progress progress("capture", options.frames, options.quiet);
  while (source->read(frame)) {
    const TrackedFace face = tracker.next(frame.image);
    if (face.status == TrackStatus::kLost) {
      ++lost;
    } else {
      (face.status == TrackStatus::kTracked ? tracked : redetected)++;
      nme.push_back(landmark_nme(face.landmarks, synth.ground_truth.landmarks.at(frame.index)));
    }
    progress.update(frame.index + 1);
  }
  progress.finish();
  std::sort(nme.begin(), nme.end());
  nlohmann::json report;
  report["input"] = {{"video", synth.video.string()}, {"frames", options.frames}, {"seed", options.seed},
                     {"kept", !options.keep_dir.empty()}};
  report["landmarks"] = {{"tracked", tracked},
                         {"redetected", redetected},
                         {"lost", lost},
                         {"nme_median", nme.empty() ? 0.0 : nme[nme.size() / 2]},
                         {"nme_max", nme.empty() ? 0.0 : nme.back()}};
  return report;
}

}  // namespace facecap
