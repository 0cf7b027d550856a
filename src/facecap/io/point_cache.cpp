#include "facecap/io/point_cache.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

static_assert(std::endian::native == std::endian::little, "PC2 is little-endian; this writer stores as the host does");

constexpr long kSampleCountOffset = 12 + 4 + 4 + 4 + 4;  // signature, version, points, start, sampling

template <typename T>
void put(std::vector<char>& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.insert(out.end(), raw, raw + sizeof(T));
}

}  // namespace

PointCacheWriter::PointCacheWriter(const std::filesystem::path& path, int points, float start_frame, float sampling)
    : path_(path), file_(std::fopen(path.c_str(), "wb")), points_(points) {
  if (!file_) throw Error("cannot write " + path.string());
  if (points <= 0 || !(sampling > 0)) throw Error("a point cache needs points and a positive sampling");
  std::vector<char> header(12, '\0');
  std::memcpy(header.data(), "POINTCACHE2", 11);
  put<int32_t>(header, 1);
  put<int32_t>(header, points);
  put<float>(header, start_frame);
  put<float>(header, sampling);
  put<int32_t>(header, 0);
  if (std::fwrite(header.data(), 1, header.size(), file_.get()) != header.size())
    throw Error("cannot write " + path.string());
}

PointCacheWriter::~PointCacheWriter() = default;

void PointCacheWriter::append(const Positions& points) {
  if (!file_) throw Error("cannot append to " + path_.string() + ": it is finished");
  if (points.cols() != points_ || !points.allFinite())
    throw Error("cannot write " + path_.string() + ": a sample is not " + std::to_string(points_) + " finite points");
  // Positions is column-major 3 x N: x y z of each point in turn, as PC2 lays them out.
  const size_t bytes = sizeof(float) * 3 * size_t(points_);
  if (std::fwrite(points.data(), 1, bytes, file_.get()) != bytes) throw Error("cannot write " + path_.string());
  ++samples_;
}

void PointCacheWriter::finish() {
  if (!file_) return;
  const int32_t samples = samples_;
  if (std::fseek(file_.get(), kSampleCountOffset, SEEK_SET) != 0 ||
      std::fwrite(&samples, sizeof(samples), 1, file_.get()) != 1 || std::fflush(file_.get()) != 0)
    throw Error("cannot write " + path_.string());
  file_.reset();
}

}  // namespace facecap
