#include "facecap/pipeline/probe.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"
#include "facecap/detect/face_detector.hpp"

namespace facecap {

ProbeReport probe_input(const std::string& spec, double start_seconds, int scan_frames) {
  auto source = open_input(spec, start_seconds);
  ProbeReport report;
  report.info = source->info();
  Frame frame;
  if (!source->read(frame) || frame.image.empty()) throw Error("cannot decode the first frame of " + spec);
  const FaceDetector detector, fine(twice_the_size({}));
  std::vector<FaceDetection> faces;
  for (int scanned = 1;; ++scanned) {
    report.face_frame = frame.index;
    // As the tracker's first search does: at twice the size where none is found.
    if (!frame.image.empty()) faces = detector.detect(frame.image);
    if (faces.empty() && !frame.image.empty()) faces = fine.detect(frame.image);
    if (!faces.empty() || scanned >= scan_frames || !source->read(frame)) break;
  }
  if (faces.empty()) report.face_frame = -1;
  report.faces = static_cast<int>(faces.size());
  for (const FaceDetection& f : faces) report.face_boxes.push_back(f.box);
  std::sort(report.face_boxes.begin(), report.face_boxes.end(),
            [](const Box& a, const Box& b) { return a.center().x() < b.center().x(); });
  return report;
}

}  // namespace facecap
