#include "facecap/pipeline/probe.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"
#include "facecap/detect/face_detector.hpp"

namespace facecap {

ProbeReport probe_input(const std::string& spec) {
  auto source = open_input(spec);
  ProbeReport report;
  report.info = source->info();
  Frame frame;
  if (!source->read(frame) || frame.image.empty()) throw Error("cannot decode the first frame of " + spec);
  // As the tracker's first search does: at twice the size where none is found.
  auto faces = FaceDetector().detect(frame.image);
  if (faces.empty()) faces = FaceDetector(twice_the_size({})).detect(frame.image);
  report.faces = static_cast<int>(faces.size());
  for (const FaceDetection& f : faces) report.face_boxes.push_back(f.box);
  std::sort(report.face_boxes.begin(), report.face_boxes.end(),
            [](const Box& a, const Box& b) { return a.center().x() < b.center().x(); });
  return report;
}

}  // namespace facecap
