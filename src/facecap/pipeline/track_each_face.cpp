#include "facecap/pipeline/track_each_face.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/pipeline/probe.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {
constexpr int kScanFrames = 300;  // 10 s at 30 fps
}  // namespace

fs::path face_folder(const fs::path& output_dir, int k) { return output_dir / ("face_" + std::to_string(k)); }

EachFaceSummary run_track_each_face(const FaceModel& model, const std::string& input, const fs::path& output_dir,
                                    const TrackOptions& options) {
  const double start = options.capture.start_seconds;
  // The first frame with a face, in the first 10 s (a video may open on black).
  const ProbeReport probe = probe_input(input, start, kScanFrames);
  if (probe.info.kind == InputKind::kCamera)
    throw Error("--all-faces needs a file: a camera cannot be read once per face (use --face to choose one)");
  if (probe.face_boxes.empty())
    throw Error("no face in the first " + std::to_string(kScanFrames) + " frames of " + input +
                ": --all-faces tracks the faces the first frame with one shows");
  ensure_writable_dir(output_dir);
  EachFaceSummary summary;
  summary.faces = probe.face_boxes;
  summary.face_frame = probe.face_frame;
  nlohmann::json list = nlohmann::json::array();
  const int n = static_cast<int>(summary.faces.size());
  for (int k = 0; k < n; ++k) {
    const Box& box = summary.faces[k];
    TrackOptions one = options;
    one.capture.tracker.pick.rule = FacePick::Rule::kNearest;
    one.capture.tracker.pick.point = box.center();
    if (!options.capture.quiet) std::fprintf(stderr, "face %d of %d (left to right)\n", k + 1, n);
    summary.runs.push_back(run_track(model, input, face_folder(output_dir, k), one));
    list.push_back({{"face", k},
                    {"folder", face_folder(output_dir, k).filename().string()},
                    {"found_in_frame", probe.face_frame},
                    {"found_box", {{"x", box.x}, {"y", box.y}, {"width", box.width}, {"height", box.height}}},
                    {"frames", summary.runs.back().capture.frames},
                    {"lost", summary.runs.back().capture.lost}});
  }
  write_text_file(output_dir / "faces.json",
                  nlohmann::json{{"input", input}, {"start_seconds", start}, {"faces", list}}.dump(2) + "\n");
  // An earlier run's folders of faces this run did not have would read as
  // this run's (as stale meshes would): removed where they hold a capture.
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(output_dir, ec)) {
    const std::string name = entry.path().filename().string();
    const std::optional<std::string_view> digits = numbered_name_digits(name, "face_", "");
    if (!digits || !entry.is_directory() || !fs::exists(entry.path() / "frames.csv")) continue;
    // More digits than an int holds is past any face this run had.
    if (digits->size() > 9 || std::stoi(std::string(*digits)) >= n) stale.push_back(entry.path());
  }
  for (const fs::path& p : stale) fs::remove_all(p, ec);
  return summary;
}

}  // namespace facecap
