#include "facecap/model/obj_reader.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"

namespace facecap {

namespace {

const char* kSquare =
    "# a unit square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl M\nf 1/1 2/2 3/3 4/4\nf 1/1 2/2 3/3\n";

void write_plain(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

void write_gz(const std::filesystem::path& p, const std::string& text) {
  gzFile f = gzopen(p.c_str(), "wb");
  gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  gzclose(f);
}

std::string error_of(const std::filesystem::path& p) {
  try {
    read_obj(p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ObjReader, ReadsPlainAndGzipAlike) {
  TempDir dir;
  write_plain(dir.path() / "a.obj", kSquare);
  write_gz(dir.path() / "a.obj.gz", kSquare);
  for (const char* name : {"a.obj", "a.obj.gz"}) {
    const ObjData obj = read_obj(dir.path() / name);
    EXPECT_EQ(obj.num_vertices(), 4);
    EXPECT_EQ(obj.uvs.size(), 4u);
    ASSERT_EQ(obj.polygons.size(), 2u);
    EXPECT_EQ(obj.polygons[0].size(), 4);
    EXPECT_EQ(obj.polygons[1].size(), 3);
    EXPECT_EQ(obj.polygons[0].v[2], 2);  // 1-based in the file, 0-based here
    EXPECT_EQ(obj.polygons[0].uv[3], 3);
  }
}

TEST(ObjReader, PositionsOnlySkipsTopology) {
  TempDir dir;
  write_plain(dir.path() / "a.obj", kSquare);
  const ObjData obj = read_obj(dir.path() / "a.obj", {.read_topology = false});
  EXPECT_EQ(obj.num_vertices(), 4);
  EXPECT_TRUE(obj.polygons.empty());
}

TEST(ObjReader, MissingFileNamesTheFile) {
  const std::string e = error_of("/nonexistent/face.obj.gz");
  EXPECT_NE(e.find("not found"), std::string::npos);
  EXPECT_NE(e.find("/nonexistent/face.obj.gz"), std::string::npos);
}

TEST(ObjReader, TruncatedGzipIsAnError) {
  TempDir dir;
  std::string big;
  for (int i = 0; i < 20000; ++i) big += "v " + std::to_string(i) + " 1.5 2.5\n";
  write_gz(dir.path() / "full.obj.gz", big);
  std::ifstream in(dir.path() / "full.obj.gz", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_plain(dir.path() / "cut.obj.gz", bytes.substr(0, bytes.size() / 2));
  const std::string e = error_of(dir.path() / "cut.obj.gz");
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  EXPECT_NE(e.find("cut.obj.gz"), std::string::npos) << e;
}

TEST(ObjReader, NanCoordinateIsAnError) {
  TempDir dir;
  write_plain(dir.path() / "nan.obj", "v 0 0 0\nv nan 1 0\n");
  EXPECT_NE(error_of(dir.path() / "nan.obj").find("non-finite"), std::string::npos);
}

TEST(ObjReader, MalformedRecordsAreErrors) {
  TempDir dir;
  write_plain(dir.path() / "bad.obj", "v 0 0\n");
  EXPECT_NE(error_of(dir.path() / "bad.obj").find("line 1"), std::string::npos);
  write_plain(dir.path() / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_NE(error_of(dir.path() / "range.obj").find("out of range"), std::string::npos);
  write_plain(dir.path() / "empty.obj", "");
  EXPECT_NE(error_of(dir.path() / "empty.obj").find("empty"), std::string::npos);
}

}  // namespace facecap
