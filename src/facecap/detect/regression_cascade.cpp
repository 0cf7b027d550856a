#include "facecap/detect/regression_cascade.hpp"

#include <cstring>
#include <fstream>
#include <string>
#include <string_view>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/binary_io.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/mapped_file.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'F', 'C', 'A', 'P', 'L', 'M', 'K', '\0'};
constexpr uint32_t kVersion = 1;
constexpr size_t kLeafAlignment = 64;  // the leaves start on a cache line of the mapped file

#pragma pack(push, 1)
struct CacheHeader {
  char magic[8];
  uint32_t version;
  uint32_t num_parts;
  uint32_t num_levels;
  uint32_t num_trees;
  uint64_t num_splits;
  uint64_t source_fingerprint;
  uint64_t payload_bytes;  // everything after the header
  uint64_t payload_hash;   // content_hash() of it
};
#pragma pack(pop)

// A checksum against a damaged file, not a cryptographic hash: four
// interleaved lanes of xor-multiply-xorshift over 8-byte words. Each step is
// a bijection of the lane, so any one changed word changes the result. Over
// memory already touched it runs at about 8 bytes a cycle (65 MB in 5.5 ms
// here); a load is the process's first touch of the mapped file, which on
// this project's VM makes it 36 ms even with the mapping populated.
uint64_t content_hash(std::span<const std::byte> bytes) {
  constexpr uint64_t kOdd = 0x9E3779B97F4A7C15ull;
  uint64_t lane[4] = {1, 2, 3, 4};
  const std::byte* p = bytes.data();
  const size_t blocks = bytes.size() / 32;
  for (size_t b = 0; b < blocks; ++b, p += 32) {
    for (int k = 0; k < 4; ++k) {
      uint64_t word;
      std::memcpy(&word, p + 8 * k, 8);
      lane[k] = (lane[k] ^ word) * kOdd;
      lane[k] ^= lane[k] >> 29;
    }
  }
  for (size_t i = blocks * 32; i < bytes.size(); ++i) lane[0] = (lane[0] ^ uint64_t(bytes[i])) * kOdd;
  uint64_t h = bytes.size();
  for (const uint64_t l : lane) h = (h ^ l) * kOdd + (h >> 31);
  return h;
}

size_t aligned(size_t offset) { return (offset + kLeafAlignment - 1) / kLeafAlignment * kLeafAlignment; }

}  // namespace

RegressionCascade::RegressionCascade(std::vector<float> initial_shape, std::vector<CascadeLevel> levels,
                                     std::vector<uint32_t> tree_split_begin, std::vector<RegressionSplit> splits,
                                     std::vector<float> leaves)
    : initial_shape_(std::move(initial_shape)),
      levels_(std::move(levels)),
      tree_split_begin_(std::move(tree_split_begin)),
      splits_(std::move(splits)),
      owned_leaves_(std::move(leaves)),
      leaves_(owned_leaves_) {
  check();
}

RegressionCascade::~RegressionCascade() = default;
RegressionCascade::RegressionCascade(RegressionCascade&&) noexcept = default;
RegressionCascade& RegressionCascade::operator=(RegressionCascade&&) noexcept = default;

// Everything add_level() and dlib's feature extraction index with is in
// range, so that a damaged or foreign file cannot make them read outside.
void RegressionCascade::check() const {
  const auto bad = [](const std::string& what) { throw Error("landmark predictor is inconsistent: " + what); };
  const size_t dims = initial_shape_.size();
  if (dims == 0 || dims % 2 != 0) bad("shape size");
  if (tree_split_begin_.empty() || tree_split_begin_.front() != 0 || tree_split_begin_.back() != splits_.size())
    bad("tree offsets");
  const size_t num_trees = tree_split_begin_.size() - 1;
  for (size_t t = 0; t < num_trees; ++t)
    if (tree_split_begin_[t + 1] < tree_split_begin_[t]) bad("tree offsets");
  if (leaves_.size() != (splits_.size() + num_trees) * dims) bad("leaf count");
  size_t next_tree = 0;
  for (const CascadeLevel& level : levels_) {
    if (level.first_tree != next_tree || level.num_trees > num_trees - next_tree) bad("trees of a level");
    next_tree += level.num_trees;
    if (level.deltas.size() != 2 * level.num_features()) bad("feature offsets");
    for (const uint32_t a : level.anchor_idx)
      if (a >= dims / 2) bad("feature anchor");
    for (uint32_t t = level.first_tree; t < level.first_tree + level.num_trees; ++t) {
      for (uint32_t s = tree_split_begin_[t]; s < tree_split_begin_[t + 1]; ++s) {
        if (splits_[s].idx1 >= level.num_features() || splits_[s].idx2 >= level.num_features()) bad("split feature");
      }
    }
  }
  if (next_tree != num_trees) bad("trees of a level");
}

void RegressionCascade::add_level(size_t level, std::span<const float> features, std::span<float> shape) const {
  const CascadeLevel& l = levels_.at(level);
  const size_t dims = initial_shape_.size();
  if (features.size() != l.num_features() || shape.size() != dims) throw Error("add_level: wrong sizes");
  // First every tree's leaf (the splits are small and stay in cache), then
  // the leaves' sum, each leaf fetched a few trees ahead: the leaves of all
  // levels are 64 MB, so each one is a run of cache misses, and waiting for
  // them one tree at a time cost most of the 68 points' time (BM_LandmarksOneFace).
  // The sum runs in tree order, so the result is the same to the bit.
  std::vector<const float*> chosen(l.num_trees);
  for (uint32_t k = 0; k < l.num_trees; ++k) {
    const uint32_t t = l.first_tree + k;
    const uint32_t begin = tree_split_begin_[t];
    const uint32_t n = tree_split_begin_[t + 1] - begin;
    const RegressionSplit* split = splits_.data() + begin;
    uint32_t i = 0;
    while (i < n) i = features[split[i].idx1] - features[split[i].idx2] > split[i].thresh ? 2 * i + 1 : 2 * i + 2;
    chosen[k] = leaves_.data() + size_t(begin + t + (i - n)) * dims;
  }
  constexpr uint32_t kAhead = 8;
  constexpr size_t kLine = 64;
  float* __restrict__ sum = shape.data();
  for (uint32_t k = 0; k < l.num_trees; ++k) {
    if (k + kAhead < l.num_trees) {
      const char* ahead = reinterpret_cast<const char*>(chosen[k + kAhead]);
      for (size_t b = 0; b < dims * sizeof(float); b += kLine) __builtin_prefetch(ahead + b);
    }
    const float* __restrict__ leaf = chosen[k];
    for (size_t d = 0; d < dims; ++d) sum[d] += leaf[d];
  }
}

void RegressionCascade::save(const fs::path& path, uint64_t source_fingerprint) const {
  ByteWriter w;
  w.floats(initial_shape_.data(), initial_shape_.size());
  for (const CascadeLevel& level : levels_) {
    w.pod(uint32_t(level.num_features()));
    w.pod(level.first_tree);
    w.pod(level.num_trees);
    w.raw(level.anchor_idx.data(), level.anchor_idx.size() * sizeof(uint32_t));
    w.floats(level.deltas.data(), level.deltas.size());
  }
  w.raw(tree_split_begin_.data(), tree_split_begin_.size() * sizeof(uint32_t));
  w.raw(splits_.data(), splits_.size() * sizeof(RegressionSplit));
  const std::string padding(aligned(sizeof(CacheHeader) + w.bytes().size()) - sizeof(CacheHeader) - w.bytes().size(),
                            '\0');
  w.raw(padding.data(), padding.size());
  w.floats(leaves_.data(), leaves_.size());
  const std::string& payload = w.bytes();

  CacheHeader header{};
  std::memcpy(header.magic, kMagic, sizeof(kMagic));
  header.version = kVersion;
  header.num_parts = uint32_t(num_parts());
  header.num_levels = uint32_t(levels_.size());
  header.num_trees = uint32_t(tree_split_begin_.size() - 1);
  header.num_splits = splits_.size();
  header.source_fingerprint = source_fingerprint;
  header.payload_bytes = payload.size();
  header.payload_hash = content_hash(std::as_bytes(std::span(payload.data(), payload.size())));
  // Header and payload written one after the other (as the model cache is),
  // not joined first into a second 67 MB string.
  write_file(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(&header), sizeof(header));
    out.write(payload.data(), std::streamsize(payload.size()));
  });
}

RegressionCascade RegressionCascade::load(const fs::path& path, uint64_t source_fingerprint) {
  auto mapped = std::make_unique<const MappedFile>(path);
  const std::span<const std::byte> bytes = mapped->bytes();
  const auto corrupt = [&](const std::string& why) {
    throw Error("landmark predictor cache " + path.string() + " is unusable: " + why);
  };
  CacheHeader header{};
  if (bytes.size() < sizeof(header)) corrupt("truncated");
  std::memcpy(&header, bytes.data(), sizeof(header));
  if (std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0) corrupt("not a facecap predictor cache");
  if (header.version != kVersion) corrupt("version " + std::to_string(header.version));
  if (header.source_fingerprint != source_fingerprint) corrupt("made from another predictor file");
  const std::span<const std::byte> payload = bytes.subspan(sizeof(header));
  if (header.payload_bytes != payload.size()) corrupt("truncated or overlong");
  if (content_hash(payload) != header.payload_hash) corrupt("damaged (checksum)");
  if (header.num_parts == 0 || header.num_parts > 10000 || header.num_levels > 1000 || header.num_trees > 10'000'000 ||
      header.num_splits > payload.size()) {
    corrupt("impossible counts");
  }

  RegressionCascade c;
  const std::string_view text(reinterpret_cast<const char*>(payload.data()), payload.size());
  ByteReader r(text, "landmark predictor cache", path);
  c.initial_shape_.resize(2 * header.num_parts);
  r.floats(c.initial_shape_.data(), c.initial_shape_.size());
  c.levels_.resize(header.num_levels);
  for (CascadeLevel& level : c.levels_) {
    const auto features = r.pod<uint32_t>();
    if (features > payload.size()) corrupt("impossible counts");
    level.first_tree = r.pod<uint32_t>();
    level.num_trees = r.pod<uint32_t>();
    level.anchor_idx.resize(features);
    r.raw(level.anchor_idx.data(), features * sizeof(uint32_t));
    level.deltas.resize(2 * size_t(features));
    r.floats(level.deltas.data(), level.deltas.size());
  }
  c.tree_split_begin_.resize(size_t(header.num_trees) + 1);
  r.raw(c.tree_split_begin_.data(), c.tree_split_begin_.size() * sizeof(uint32_t));
  c.splits_.resize(header.num_splits);
  r.raw(c.splits_.data(), c.splits_.size() * sizeof(RegressionSplit));
  const size_t leaves_at = aligned(bytes.size() - payload.size() + (payload.size() - r.remaining()));
  const size_t num_leaves = (header.num_splits + header.num_trees) * 2 * header.num_parts;
  if (leaves_at + num_leaves * sizeof(float) != bytes.size()) corrupt("leaf count");
  c.leaves_ = std::span(reinterpret_cast<const float*>(bytes.data() + leaves_at), num_leaves);
  c.mapped_ = std::move(mapped);
  c.check();
  return c;
}

}  // namespace facecap
