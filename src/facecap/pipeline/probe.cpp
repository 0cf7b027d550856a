#include "facecap/pipeline/probe.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/turned_faces.hpp"

namespace facecap {

ProbeReport probe_input(const std::string& spec) {
  auto source = open_input(spec);
  ProbeReport report;
  report.info = source->info();
  Frame frame;
  if (!source->read(frame) || frame.image.empty()) throw Error("cannot decode the first frame of " + spec);
  // As the tracker's first search does: at twice the size where none is
  // found upright, then in the other turns, then halfway between them.
  auto faces = FaceDetector().detect(frame.image);
  if (faces.empty()) faces = FaceDetector(twice_the_size({})).detect(frame.image);
  for (const FaceDetection& f : faces) report.found.push_back({f.box, 0});
  if (faces.empty()) {
    const std::span<const float> turned(kFaceTurns.begin() + 1, kFaceTurns.end());
    const FaceDetector detector;
    for (const TurnedFace& f : find_first_turned_faces(detector, frame.image, turned, FaceDetectorOptions{}.max_side))
      report.found.push_back({UprightView(frame.image.size(), f.degrees).to_frame(f.in_view.box), f.degrees});
  }
  report.faces = static_cast<int>(report.found.size());
  std::sort(report.found.begin(), report.found.end(),
            [](const ProbeFace& a, const ProbeFace& b) { return a.box.center().x() < b.box.center().x(); });
  return report;
}

}  // namespace facecap
