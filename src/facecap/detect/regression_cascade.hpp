#pragma once
// The 68-point landmark predictor's cascade of regression forests (Kazemi and
// Sullivan 2014, as dlib's shape_predictor holds it) in a flat layout: every
// tree's splits in one array and every leaf in another. A cache file holds
// the arrays as they lie in memory, so that later runs map it (a few
// milliseconds) instead of decoding dlib's serialisation of the same 65 MB of
// leaves (about half a second). No dlib here: dlib_backend.cpp converts.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

namespace facecap {

class MappedFile;

// One node of a tree: go to child 2i+1 when feature[idx1] - feature[idx2] >
// thresh, else to 2i+2 (dlib's regression_tree).
struct RegressionSplit {
  uint32_t idx1 = 0;
  uint32_t idx2 = 0;
  float thresh = 0;
};

// One level of the cascade: where its feature pixels lie (each an offset from
// a landmark of the current shape, in the mean shape's frame) and its trees.
struct CascadeLevel {
  std::vector<uint32_t> anchor_idx;  // per feature pixel: the landmark
  std::vector<float> deltas;         // per feature pixel: x, y of its offset
  uint32_t first_tree = 0;
  uint32_t num_trees = 0;
  size_t num_features() const { return anchor_idx.size(); }
};

class RegressionCascade {
 public:
  // Tree t has splits [tree_split_begin[t], tree_split_begin[t + 1]) and one
  // leaf more than splits, each leaf a shape increment of
  // initial_shape.size() floats; tree t's first leaf is leaf
  // tree_split_begin[t] + t. Throws facecap::Error when the parts disagree.
  RegressionCascade(std::vector<float> initial_shape, std::vector<CascadeLevel> levels,
                    std::vector<uint32_t> tree_split_begin, std::vector<RegressionSplit> splits,
                    std::vector<float> leaves);
  ~RegressionCascade();
  RegressionCascade(RegressionCascade&&) noexcept;
  RegressionCascade& operator=(RegressionCascade&&) noexcept;

  // Reads a file written by save() for the source whose fingerprint is
  // `source_fingerprint`; throws facecap::Error when it is missing, for
  // another source or version, truncated or damaged.
  static RegressionCascade load(const std::filesystem::path& path, uint64_t source_fingerprint);
  // Writes it atomically.
  void save(const std::filesystem::path& path, uint64_t source_fingerprint) const;

  int num_parts() const { return int(initial_shape_.size() / 2); }
  const std::vector<float>& initial_shape() const { return initial_shape_; }
  const std::vector<CascadeLevel>& levels() const { return levels_; }
  // shape += the leaves that `level`'s trees reach from its feature pixels'
  // values, tree after tree (the order dlib adds them in).
  void add_level(size_t level, std::span<const float> features, std::span<float> shape) const;

 private:
  RegressionCascade() = default;
  void check() const;

  std::vector<float> initial_shape_;
  std::vector<CascadeLevel> levels_;
  std::vector<uint32_t> tree_split_begin_;
  std::vector<RegressionSplit> splits_;
  std::vector<float> owned_leaves_;           // built from dlib's file
  std::unique_ptr<const MappedFile> mapped_;  // or mapped from the cache
  std::span<const float> leaves_;             // into one of the two
};

}  // namespace facecap
