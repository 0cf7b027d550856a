#pragma once
#include <limits>
// The training set of the expression mappings (§5.2.3; SAVEE is not
// available to us, DESIGN.md). Recipe:
//  - neutral domain: per-frame weights our tracker recovers on real talking
//    footage (frames.csv files of `facecap track`);
//  - each emotion domain: its FACS prototype (emotions.hpp) at a random
//    intensity (0.35-1.0) with per-side asymmetry (+-15%), laid over a random
//    frame of the neutral speech (the larger of the two per shape), so that
//    the mapping learns to keep speech while adding the emotion;
//  - plus tracked real frames where footage shows the emotion (frames.csv
//    and a time range), repeated to make up a share of that domain (15 %).
// Rows of the CSV: a label, then the 53 weights under their ARKit names.
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "facecap/expr/emotions.hpp"

namespace facecap {

struct LabeledWeights {
  Emotion label = Emotion::kNeutral;
  Eigen::VectorXf weights;
};

// The weights of the tracked (not lost) frames of a `facecap track` frames.csv
// between two times (seconds), in the order of `names`. Throws
// facecap::Error naming the file and the missing column when the file is not
// a frames.csv.
std::vector<Eigen::VectorXf> read_tracked_weights(const std::filesystem::path& csv,
                                                  const std::vector<std::string>& names, double from_seconds = 0,
                                                  double to_seconds = std::numeric_limits<double>::infinity());

std::vector<LabeledWeights> make_emotion_samples(Emotion emotion, const std::vector<Eigen::VectorXf>& speech,
                                                 const std::vector<std::string>& names, int count, uint64_t seed);

void write_dataset_csv(const std::filesystem::path& path, const std::vector<LabeledWeights>& rows,
                       const std::vector<std::string>& names);
// Throws facecap::Error naming the file (and the line) when it is malformed.
std::vector<LabeledWeights> read_dataset_csv(const std::filesystem::path& path, const std::vector<std::string>& names);

}  // namespace facecap
