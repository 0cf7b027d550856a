#pragma once
// truth.json: every parameter of a synthetic performance, per frame, and the
// 2D landmarks a perfect detector would mark. Written by `facecap synth`,
// read back by the evaluations.
#include <filesystem>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/synth/performance.hpp"

namespace facecap {

struct SynthTruth {
  SynthPerformance performance;
  std::vector<std::string> expression_names;
  std::vector<Landmarks> landmarks;         // silhouette-aware, as a detector marks them
  std::vector<Landmarks> vertex_landmarks;  // projections of the fixed landmark vertices
};

void write_truth(const std::filesystem::path& path, const SynthTruth& truth);
// Throws facecap::Error naming the file when it is missing or malformed.
SynthTruth read_truth(const std::filesystem::path& path);

}  // namespace facecap
