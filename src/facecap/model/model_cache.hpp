#pragma once
// Versioned binary cache of a loaded FaceModel (float32 payload, a header with
// the counts, a fingerprint of the source files and a CRC-32 of the payload),
// so that later loads take a fraction of a second instead of parsing 150 OBJs.
#include <cstdint>
#include <filesystem>

#include "facecap/model/face_model.hpp"

namespace facecap {

inline constexpr uint32_t kModelCacheVersion = 1;

void write_model_cache(const FaceModel& model, uint64_t source_fingerprint, const std::filesystem::path& path);

// Reads a cache file. Throws facecap::Error if it is missing, truncated,
// corrupt (bad magic, CRC mismatch, impossible counts) or of another version.
// `expected_fingerprint`, when non-zero, must match the stored one.
FaceModel read_model_cache(const std::filesystem::path& path, uint64_t expected_fingerprint = 0);

// Fingerprint of the model source files: names, sizes and modification times.
uint64_t model_source_fingerprint(const std::filesystem::path& model_dir);

// Where the cache of a model folder lives (under cache_dir()).
std::filesystem::path model_cache_path(const std::filesystem::path& model_dir);

struct ModelLoadReport {
  bool from_cache = false;
  bool cache_written = false;
  std::filesystem::path cache_file;
  double seconds = 0.0;
};

// Loads the model through its cache: reads the cache when it is present and
// current, otherwise parses the OBJ folder and (re)writes the cache. A cache
// that cannot be written is not an error (the model is still returned).
FaceModel load_face_model(const std::filesystem::path& model_dir, ModelLoadReport* report = nullptr);

}  // namespace facecap
