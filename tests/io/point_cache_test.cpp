#include "facecap/io/point_cache.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

template <typename T>
T at(const std::string& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

}  // namespace

// The PC2 layout: the signature, version 1, the point count, the start
// frame and sampling, the sample count filled in at the end, then each
// sample's points as x y z floats. A bad sample adds nothing.
TEST(PointCache, WritesThePc2LayoutAndFillsInTheSampleCount) {
  TempDir dir;
  const auto file = dir.path() / "face.pc2";
  PointCacheWriter writer(file, 2, 12.0f);
  Positions sample(3, 2);
  for (int s = 0; s < 3; ++s) {
    sample.col(0) = Vec3f(float(s), 2.0f, 4.0f);
    sample.col(1) = Vec3f(1.0f, 3.0f, float(-s));
    writer.append(sample);
  }
  Positions nan = sample;
  nan(1, 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(writer.append(nan), Error);
  EXPECT_THROW(writer.append(Positions::Zero(3, 3)), Error);
  EXPECT_EQ(writer.samples(), 3);
  writer.finish();
  EXPECT_THROW(writer.append(sample), Error);

  const std::string bytes = test::read_file(file);
  ASSERT_EQ(bytes.size(), 32u + 3 * 2 * 3 * 4);
  EXPECT_EQ(bytes.substr(0, 12), std::string("POINTCACHE2\0", 12));
  EXPECT_EQ(at<int32_t>(bytes, 12), 1);
  EXPECT_EQ(at<int32_t>(bytes, 16), 2);
  EXPECT_EQ(at<float>(bytes, 20), 12.0f);
  EXPECT_EQ(at<float>(bytes, 24), 1.0f);
  EXPECT_EQ(at<int32_t>(bytes, 28), 3);
  for (int s = 0; s < 3; ++s) {
    const size_t sample_at = 32 + size_t(s) * 24;
    EXPECT_EQ(at<float>(bytes, sample_at + 0), float(s));
    EXPECT_EQ(at<float>(bytes, sample_at + 4), 2.0f);
    EXPECT_EQ(at<float>(bytes, sample_at + 8), 4.0f);
    EXPECT_EQ(at<float>(bytes, sample_at + 12), 1.0f);
    EXPECT_EQ(at<float>(bytes, sample_at + 16), 3.0f);
    EXPECT_EQ(at<float>(bytes, sample_at + 20), float(-s));
  }
}

TEST(PointCache, AnUnwritablePathIsAClearError) {
  TempDir dir;
  EXPECT_THROW(PointCacheWriter(dir.path() / "missing" / "face.pc2", 4, 0.0f), Error);
  EXPECT_THROW(PointCacheWriter(dir.path() / "face.pc2", 0, 0.0f), Error);
}

}  // namespace facecap
