#include "facecap/pipeline/track_each_face.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string_view>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/io/image_file.hpp"

namespace facecap {

namespace fs = std::filesystem;

fs::path face_folder(const fs::path& output_dir, int k) { return output_dir / ("face_" + std::to_string(k)); }

cv::Mat faces_contact_sheet(const std::vector<FoundFace>& faces) {
  const int tile = FoundFace::kThumbnailSize, label = 20, columns = std::min<int>(8, std::max<size_t>(1, faces.size()));
  const int rows = (static_cast<int>(faces.size()) + columns - 1) / columns;
  cv::Mat sheet(std::max(1, rows) * (tile + label), columns * tile, CV_8UC3, cv::Scalar::all(255));
  for (size_t k = 0; k < faces.size(); ++k) {
    const int x = static_cast<int>(k) % columns * tile, y = static_cast<int>(k) / columns * (tile + label);
    if (!faces[k].thumbnail.empty()) faces[k].thumbnail.copyTo(sheet(cv::Rect(x, y, tile, tile)));
    const std::string text = "face_" + std::to_string(faces[k].index) + " @" + std::to_string(faces[k].first_frame);
    cv::putText(sheet, text, cv::Point(x + 4, y + tile + 14), cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  }
  return sheet;
}

EachFaceSummary run_track_each_face(const FaceModel& model, const std::string& input, const fs::path& output_dir,
                                    const TrackOptions& options, const AllFacesOptions& all) {
  auto source = open_input(input, options.capture.start_seconds);  // validates the input before anything is written
  // A run that fails (no face, Ctrl-C) leaves no folder it made: the files
  // in them are removed first, as the outputs go (declared after this).
  FoldersMadeHere made;
  made.add(output_dir);
  ensure_writable_dir(output_dir);
  if (options.livelink_stream) UdpSender{options.livelink_stream->target};  // an unknown host fails before the work
  std::vector<std::unique_ptr<TrackOutput>> outputs;
  CaptureOptions capture = options.capture;
  capture.keep_images = options.needs_images();
  EachFaceSummary summary;
  summary.capture =
      run_capture_all_faces(model, *source, capture, all, [&](const FoundFace& face, const InputInfo& info) {
        if (!options.capture.quiet)
          std::fprintf(stderr, "\rfacecap: face %d found in frame %d at (%.0f, %.0f)\n", face.index, face.first_frame,
                       face.box.center().x(), face.box.center().y());
        made.add(face_folder(output_dir, face.index));
        // The face's capture starts where it was found: of --max-frames, it
        // sees what is left (its overlay's sound ends with its last frame).
        TrackOptions own = options;
        if (own.livelink_stream) own.livelink_stream->subject += "_face" + std::to_string(face.index);
        if (own.capture.max_frames > 0)
          own.capture.max_frames =
              std::max(1, own.capture.max_frames - (face.first_frame - source->info().first_frame));
        outputs.push_back(std::make_unique<TrackOutput>(model, info, input, face_folder(output_dir, face.index), own));
        return outputs.back()->sink();
      });
  summary.faces = summary.capture.faces;
  if (summary.faces.empty()) {
    const std::string damage = input_damage_note(summary.capture.damage, "it");
    throw Error("no face found in the " + std::to_string(summary.capture.timings.frames) + " frame(s) of " + input +
                (damage.empty() ? "" : "; " + damage));
  }
  nlohmann::json list = nlohmann::json::array();
  for (size_t k = 0; k < summary.faces.size(); ++k) {
    const FoundFace& face = summary.faces[k];
    summary.runs.push_back(outputs[k]->finish(summary.capture.captures[k]));
    const Box& box = face.box;
    list.push_back({{"face", face.index},
                    {"folder", face_folder(output_dir, face.index).filename().string()},
                    {"found_in_frame", face.first_frame},
                    {"found_at_time", face.first_time},
                    {"found_in_shot", face.shot},
                    {"found_box", {{"x", box.x}, {"y", box.y}, {"width", box.width}, {"height", box.height}}},
                    {"frames", summary.runs.back().capture.frames},
                    {"lost", summary.runs.back().capture.lost}});
  }
  const std::vector<uint8_t> sheet = encode_png(faces_contact_sheet(summary.faces));
  write_binary_file(output_dir / "faces.png", sheet.data(), sheet.size());
  write_text_file(output_dir / "faces.json", nlohmann::json{{"input", input},
                                                            {"start_seconds", options.capture.start_seconds},
                                                            {"frames", summary.capture.timings.frames},
                                                            {"uncaptured_faces", summary.capture.uncaptured_faces},
                                                            {"faces", list}}
                                                     .dump(2) +
                                                 "\n");
  made.keep();
  // An earlier run's folders of faces this run did not have would read as
  // this run's (as stale meshes would): removed where they hold a capture.
  const int n = static_cast<int>(summary.faces.size());
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
