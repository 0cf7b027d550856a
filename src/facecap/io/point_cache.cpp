#include "facecap/io/point_cache.hpp"

#include <bit>
#include <cstdint>
#include <string>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/binary_io.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

static_assert(std::endian::native == std::endian::little, "PC2 is little-endian; this writer stores as the host does");

constexpr long kSampleCountOffset = 12 + 4 + 4 + 4 + 4;  // signature, version, points, start, sampling

}  // namespace

PointCacheWriter::PointCacheWriter(const std::filesystem::path& path, int points, float start_frame, float sampling)
    : path_(path), file_(std::fopen(path.c_str(), "wb")), points_(points) {
  if (!file_) throw Error("cannot write " + path.string());
  if (points <= 0 || !(sampling > 0)) throw Error("a point cache needs points and a positive sampling");
  ByteWriter header;
  header.raw("POINTCACHE2", 12);  // with its terminating zero
  header.pod<int32_t>(1);
  header.pod<int32_t>(points);
  header.pod<float>(start_frame);
  header.pod<float>(sampling);
  header.pod<int32_t>(0);  // the samples, filled in by finish()
  if (std::fwrite(header.bytes().data(), 1, header.bytes().size(), file_.get()) != header.bytes().size())
    throw Error(write_failure(path));
}

PointCacheWriter::~PointCacheWriter() = default;

void PointCacheWriter::append(const Positions& points) {
  if (!file_) throw Error("cannot append to " + path_.string() + ": it is finished");
  if (points.cols() != points_ || !points.allFinite())
    throw Error("cannot write " + path_.string() + ": a sample is not " + std::to_string(points_) + " finite points");
  // Positions is column-major 3 x N: x y z of each point in turn, as PC2 lays them out.
  const size_t bytes = sizeof(float) * 3 * size_t(points_);
  if (std::fwrite(points.data(), 1, bytes, file_.get()) != bytes) throw Error(write_failure(path_));
  ++samples_;
}

void PointCacheWriter::finish() {
  if (!file_) return;
  const int32_t samples = samples_;
  if (std::fseek(file_.get(), kSampleCountOffset, SEEK_SET) != 0 ||
      std::fwrite(&samples, sizeof(samples), 1, file_.get()) != 1 || std::fflush(file_.get()) != 0)
    throw Error(write_failure(path_));
  file_.reset();
}

}  // namespace facecap
