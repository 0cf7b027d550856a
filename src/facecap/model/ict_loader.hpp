#pragma once
// Loads the ICT Face Model Light from its folder of OBJ files (plain or gzip)
// and vertex_indices.json, checking every file against the expected shape.
#include <filesystem>

#include "facecap/model/face_model.hpp"

namespace facecap {

struct IctLoadOptions {
  int num_identity = 100;  // identity modes to load (identity000 .. identity{n-1})
};

// Throws facecap::Error naming the offending file on any problem: missing
// folder or file, truncated or corrupt OBJ, wrong vertex count, non-finite
// value, expression listed in vertex_indices.json but absent.
FaceModel load_ict_model(const std::filesystem::path& dir, const IctLoadOptions& options = {});

// The model files a folder must hold (neutral, identities, expressions, JSON),
// resolved to .obj or .obj.gz; used to fingerprint the cache.
std::vector<std::filesystem::path> ict_source_files(const std::filesystem::path& dir,
                                                    const IctLoadOptions& options = {});

}  // namespace facecap
