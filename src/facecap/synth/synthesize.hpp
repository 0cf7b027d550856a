#pragma once
// `facecap synth`: renders a synthetic performance to DIR/video.mp4 with its
// ground truth (DIR/truth.json) and albedo texture (DIR/albedo.png).
#include <filesystem>

#include "facecap/synth/truth_io.hpp"

namespace facecap {

struct SynthJobResult {
  std::filesystem::path video;
  std::filesystem::path truth;
  std::filesystem::path albedo;
  SynthTruth ground_truth;
  double seconds = 0;
};

SynthJobResult synthesize(const FaceModel& model, const SynthOptions& options, const std::filesystem::path& out_dir,
                          bool quiet = false);

}  // namespace facecap
