#pragma once
// `facecap demo`: the main job on the default input. Synthesises a short
// performance with known parameters, runs the capture pipeline on the video,
// and reports what was recovered against the truth.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "facecap/model/face_model.hpp"

namespace facecap {

struct DemoOptions {
  int frames = 60;
  uint64_t seed = 7;
  std::string keep_dir;  // empty: a temporary folder, removed afterwards
  bool quiet = false;
};

nlohmann::json run_demo(const FaceModel& model, const DemoOptions& options);

}  // namespace facecap
