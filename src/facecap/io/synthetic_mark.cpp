#include "facecap/io/synthetic_mark.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <ctime>
#include <nlohmann/json.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/version.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/marked_image.hpp"

namespace facecap {

std::map<std::string, std::string> synthetic_metadata(const SyntheticMark& mark) {
  return {{"synthetic", "true"},
          {"facecap_edit", mark.kind},
          {"comment", "SYNTHETIC MEDIA: " + mark.description + " Made with facecap " + kFacecapVersion + "."},
          {"encoder_note", "facecap " + std::string(kFacecapVersion)}};
}

std::filesystem::path sidecar_path(const std::filesystem::path& media_path) { return media_path.string() + ".json"; }

void write_synthetic_sidecar(const std::filesystem::path& media_path, const SyntheticMark& mark,
                             const std::filesystem::path& to) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json j;
  j["synthetic"] = true;
  j["media"] = media_path.filename().string();
  j["edit"] = mark.kind;
  j["description"] = mark.description;
  j["sources"] = mark.sources;
  j["parameters"] = mark.parameters;
  j["tool"] = {{"name", "facecap"}, {"version", kFacecapVersion}};
  j["created_utc"] = stamp;
  j["notice"] =
      "This media was generated or altered by software. It does not show a real recording of what it depicts.";
  write_text_file(to.empty() ? sidecar_path(media_path) : to, j.dump(2) + "\n");
}

bool carries_synthetic_marks(const std::filesystem::path& media_path) {
  // Matroska's tag names are upper case (SYNTHETIC), mp4's as written; an
  // image's are its text chunks or XMP.
  const auto tags = is_still_image_path(media_path) ? read_image_tags(media_path) : read_container_tags(media_path);
  const bool tagged = std::any_of(tags.begin(), tags.end(), [](const auto& tag) {
    std::string key = tag.first;
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return key == "synthetic" && tag.second == "true";
  });
  return tagged && std::filesystem::exists(sidecar_path(media_path));
}

}  // namespace facecap
