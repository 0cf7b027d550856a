// Face detection benchmarks: dlib's HOG detector over a whole 1280x720 frame
// of address_720p_a, searched at several sizes (the longer side after the
// detector's resize). The smallest face it finds is about 80 px at the
// searched size, so the cost of finding smaller faces grows with the square
// of the size. Skips where the footage is absent.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/core/paths.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

namespace {

cv::Mat first_frame_grey() {
  const std::filesystem::path video = default_data_dir() / "address_720p_a.mp4";
  if (!std::filesystem::exists(video)) return {};
  Frame frame;
  if (!open_input(video.string())->read(frame)) return {};
  cv::Mat grey;
  cv::cvtColor(frame.image, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

void BM_DetectWholeFrame(benchmark::State& state) {
  static const cv::Mat grey = first_frame_grey();
  if (grey.empty()) {
    state.SkipWithError("address_720p_a.mp4 not found in the data folder");
    return;
  }
  const int side = static_cast<int>(state.range(0));
  const FaceDetector detector(FaceDetectorOptions{.max_side = side, .min_side = side});
  size_t faces = 0;
  for (auto _ : state) faces = detector.detect(grey).size();
  state.counters["faces"] = double(faces);
}
BENCHMARK(BM_DetectWholeFrame)->Arg(640)->Arg(960)->Arg(1280)->Arg(1920)->Unit(benchmark::kMillisecond);

// dlib's 68 points on the frame's face, from its detector box: what tracking
// costs per frame besides the verification (the cascade's 15 levels of 500
// trees read about 2.7 MB of its 64 MB of leaves).
// The frame's largest face, or nothing with the benchmark skipped and told why.
std::optional<Box> first_face(const cv::Mat& grey, benchmark::State& state) {
  if (grey.empty()) {
    state.SkipWithError("address_720p_a.mp4 not found in the data folder");
    return std::nullopt;
  }
  const std::vector<FaceDetection> faces = FaceDetector().detect(grey);
  if (faces.empty()) {
    state.SkipWithError("no face found in the frame");
    return std::nullopt;
  }
  return faces.front().box;
}

void BM_LandmarksOneFace(benchmark::State& state) {
  static const cv::Mat grey = first_frame_grey();
  const std::optional<Box> face = first_face(grey, state);
  if (!face) return;
  const LandmarkDetector landmarks;
  for (auto _ : state) benchmark::DoNotOptimize(landmarks.detect(grey, *face));
}
BENCHMARK(BM_LandmarksOneFace)->Unit(benchmark::kMicrosecond);

// The tracker's per-frame check that a face is still there: the detector on a
// crop 1.6 times the face, scaled to 130 px (FaceTracker's verifier).
void BM_VerifyFaceCrop(benchmark::State& state) {
  static const cv::Mat grey = first_frame_grey();
  const std::optional<Box> face = first_face(grey, state);
  if (!face) return;
  const Box& b = *face;
  const Box crop{b.center().x() - 0.8f * b.width, b.center().y() - 0.8f * b.height, 1.6f * b.width, 1.6f * b.height};
  const FaceDetector verifier(
      FaceDetectorOptions{.max_side = 130, .min_side = 130, .upsample = 0, .adjust_threshold = -0.4});
  size_t found = 0;
  for (auto _ : state) found = verifier.detect_in(grey, crop).size();
  state.counters["faces"] = double(found);
}
BENCHMARK(BM_VerifyFaceCrop)->Unit(benchmark::kMicrosecond);

}  // namespace

}  // namespace facecap
