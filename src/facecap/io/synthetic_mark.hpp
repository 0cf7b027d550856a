#pragma once
// The marks every synthetic or manipulated output of facecap carries:
// container metadata (mp4 tags `synthetic=true`, `facecap_edit=<kind>` and a
// human-readable `comment`; a photo's in its XMP and text, marked_image.hpp)
// and a sidecar JSON `<output>.json` that states
// what was done, from which inputs, by which version, and when.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace facecap {

struct SyntheticMark {
  std::string kind;                  // "synthetic-render", "expression-transform", "face-swap"
  std::string description;           // one sentence for people
  std::vector<std::string> sources;  // input files the output was made from
  std::map<std::string, std::string> parameters;
};

// Tags for VideoWriterOptions::metadata.
std::map<std::string, std::string> synthetic_metadata(const SyntheticMark& mark);

// Writes `<media_path>.json` (atomically), or, with `to`, writes it there
// (a staged name: atomic_file.hpp's StagedFiles), still describing media_path.
void write_synthetic_sidecar(const std::filesystem::path& media_path, const SyntheticMark& mark,
                             const std::filesystem::path& to = {});

// The sidecar path for an output file.
std::filesystem::path sidecar_path(const std::filesystem::path& media_path);

// True when a video or image carries both marks: the `synthetic=true` tag (an
// image's: marked_image.hpp) and its sidecar.
bool carries_synthetic_marks(const std::filesystem::path& media_path);

}  // namespace facecap
