#include "facecap/model/model_cache.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

FaceModel tiny_model() {
  FaceModel m;
  m.num_vertices = 3;
  m.neutral = Eigen::VectorXf::LinSpaced(9, 0, 8);
  m.identity_basis = Eigen::MatrixXf::Random(9, 2);
  m.expression_basis = Eigen::MatrixXf::Random(9, 1);
  m.expression_names = {"jawOpen"};
  Polygon p;
  p.v = {0, 1, 2, -1};
  p.uv = {0, 1, 2, -1};
  m.polygons = {p};
  m.uvs = {Vec2f(0, 0), Vec2f(1, 0), Vec2f(0, 1)};
  m.landmarks.vertices = {0, 1, 2};
  m.landmarks.jaw_left = {1};
  return m;
}

std::string read_error(const fs::path& p, uint64_t fingerprint = 0) {
  try {
    read_model_cache(p, fingerprint);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ModelCache, RoundTripsEveryField) {
  TempDir dir;
  const FaceModel m = tiny_model();
  write_model_cache(m, 42, dir.path() / "m.fcm");
  const FaceModel r = read_model_cache(dir.path() / "m.fcm", 42);
  EXPECT_EQ(r.num_vertices, 3);
  EXPECT_TRUE(r.neutral.isApprox(m.neutral));
  EXPECT_TRUE(r.identity_basis.isApprox(m.identity_basis));
  EXPECT_TRUE(r.expression_basis.isApprox(m.expression_basis));
  EXPECT_EQ(r.expression_names, m.expression_names);
  EXPECT_EQ(r.polygons[0].v, m.polygons[0].v);
  EXPECT_EQ(r.uvs[2], m.uvs[2]);
  EXPECT_EQ(r.landmarks.vertices, m.landmarks.vertices);
  EXPECT_EQ(r.landmarks.jaw_left, m.landmarks.jaw_left);
}

TEST(ModelCache, CorruptTruncatedAndStaleCachesAreRejected) {
  TempDir dir;
  const fs::path p = dir.path() / "m.fcm";
  write_model_cache(tiny_model(), 42, p);
  EXPECT_NE(read_error(p, 43).find("stale"), std::string::npos);

  std::string bytes;
  {
    std::ifstream in(p, std::ios::binary);
    bytes.assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  std::string flipped = bytes;
  flipped[flipped.size() - 20] ^= 0x5a;
  std::ofstream(dir.path() / "flip.fcm", std::ios::binary) << flipped;
  EXPECT_NE(read_error(dir.path() / "flip.fcm").find("checksum"), std::string::npos);

  std::ofstream(dir.path() / "cut.fcm", std::ios::binary) << bytes.substr(0, bytes.size() - 7);
  EXPECT_NE(read_error(dir.path() / "cut.fcm").find("truncated"), std::string::npos);

  std::ofstream(dir.path() / "junk.fcm", std::ios::binary) << std::string(200, 'x');
  EXPECT_NE(read_error(dir.path() / "junk.fcm").find("not a facecap model cache"), std::string::npos);
}

TEST(ModelCache, LoadThroughCacheRebuildsAStaleOrDamagedCache) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir cache;
  ::setenv("FACECAP_CACHE_DIR", cache.path().c_str(), 1);
  ModelLoadReport first, second, third;
  const FaceModel a = load_face_model(default_model_dir(), &first);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(first.cache_written);
  const FaceModel b = load_face_model(default_model_dir(), &second);
  EXPECT_TRUE(second.from_cache);
  EXPECT_TRUE(a.expression_basis.isApprox(b.expression_basis));
  // Damage the cache: the next load parses the OBJs again and rewrites it.
  {
    std::fstream f(second.cache_file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(4000);
    f.put('\x7f');
  }
  const FaceModel c = load_face_model(default_model_dir(), &third);
  EXPECT_FALSE(third.from_cache);
  EXPECT_TRUE(third.cache_written);
  EXPECT_TRUE(a.neutral.isApprox(c.neutral));
  ::unsetenv("FACECAP_CACHE_DIR");
}

}  // namespace facecap
