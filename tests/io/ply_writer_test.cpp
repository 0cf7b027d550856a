#include "facecap/io/ply_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "io/ply_reader.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;
using test::Ply;
using test::read_file;

namespace {

struct Sample {
  Positions positions{3, 5};
  Positions normals{3, 5};
  Positions colours{3, 5};
  std::vector<Vec2f> uvs{{0, 0}, {1, 0}, {1, 1}, {0.25f, 0.125f}, {0.5f, 0.75f}};
  std::vector<Polygon> polygons;

  Sample() {
    positions << 0.0f, 1.0f, 1.0f, 0.0f, -2.5f,  //
        0.0f, 0.0f, 1.0f, 1.0f, 0.000004f,       //
        10.123456f, -0.5f, 0.0f, 0.0f, 123.45678f;
    normals.setZero();
    normals.row(2).setConstant(1.0f);
    normals.col(4) = Vec3f(0.6f, 0.0f, 0.8f);
    colours << 0.0f, 1.0f, 0.5f, 1.5f, 0.2f,  //
        0.0f, 0.0f, 0.25f, -0.5f, 0.4f,       //
        1.0f, 0.0f, 0.75f, 0.0f, 0.6f;
    Polygon quad, tri;
    quad.v = {0, 1, 2, 3};
    tri.v = {2, 4, 3, -1};
    polygons = {quad, tri};
  }
};

// The mesh's positions and faces alone; a test adds what it needs.
PlyMesh bare(const Positions& positions, const std::vector<Polygon>& polygons) {
  PlyMesh m;
  m.positions = &positions;
  m.polygons = &polygons;
  return m;
}

PlyMesh with_colours(PlyMesh m, const Positions& colours) {
  m.colours = &colours;
  return m;
}

}  // namespace

// The header as the format (and MeshLab, Blender, Open3D) reads it, and every
// value back: floats exactly, colours rounded to 8 bits and clamped, quads
// and triangles as lists of their own length.
TEST(PlyWriter, WritesEveryAttributeAndReadsBack) {
  const Sample s;
  TempDir dir;
  const fs::path file = dir.path() / "a.ply";
  write_ply(file, {.positions = &s.positions,
                   .polygons = &s.polygons,
                   .normals = &s.normals,
                   .colours = &s.colours,
                   .uvs = &s.uvs,
                   .comment = "facecap test\nsecond line"});
  const std::string bytes = read_file(file);
  EXPECT_EQ(bytes.substr(0, bytes.find("end_header\n") + 11),
            "ply\nformat binary_little_endian 1.0\ncomment facecap test\ncomment second line\n"
            "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            "property float s\nproperty float t\n"
            "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
  // 5 vertices of 3 + 3 + 2 floats and 3 bytes; a quad (1 + 16 bytes) and a triangle (1 + 12).
  EXPECT_EQ(bytes.size(), bytes.find("end_header\n") + 11 + 5 * (8 * 4 + 3) + 17 + 13);

  const Ply ply = Ply::read(file);
  EXPECT_EQ(ply.comments, (std::vector<std::string>{"facecap test", "second line"}));
  ASSERT_EQ(ply.vertices(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(ply.point(i), s.positions.col(Eigen::Index(i)).cast<double>()) << i;
    EXPECT_EQ(ply.point(i, "nx", "ny", "nz"), s.normals.col(Eigen::Index(i)).cast<double>()) << i;
    EXPECT_EQ(ply.vertex.at("s")[i], double(s.uvs[i].x())) << i;
    EXPECT_EQ(ply.vertex.at("t")[i], double(s.uvs[i].y())) << i;
  }
  EXPECT_EQ(ply.vertex.at("red"), (std::vector<double>{0, 255, 128, 255, 51}));
  EXPECT_EQ(ply.vertex.at("green"), (std::vector<double>{0, 0, 64, 0, 102}));
  EXPECT_EQ(ply.vertex.at("blue"), (std::vector<double>{255, 0, 191, 0, 153}));
  EXPECT_EQ(ply.faces, (std::vector<std::vector<int>>{{0, 1, 2, 3}, {2, 4, 3}}));
}

// Only the attributes given are declared.
TEST(PlyWriter, DeclaresOnlyTheAttributesGiven) {
  const Sample s;
  TempDir dir;
  write_ply(dir.path() / "bare.ply", bare(s.positions, s.polygons));
  const Ply plain = Ply::read(dir.path() / "bare.ply");
  EXPECT_EQ(plain.vertex_properties, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_TRUE(plain.comments.empty());
  EXPECT_EQ(plain.faces.size(), 2u);
  write_ply(dir.path() / "coloured.ply", with_colours(bare(s.positions, s.polygons), s.colours));
  EXPECT_EQ(Ply::read(dir.path() / "coloured.ply").vertex_properties,
            (std::vector<std::string>{"x", "y", "z", "red", "green", "blue"}));
}

// A mesh that would make a broken file is refused, and what was at the path
// stays as it was.
TEST(PlyWriter, ABrokenMeshIsRefusedAndTheFileLeftAlone) {
  Sample s;
  TempDir dir;
  const fs::path file = dir.path() / "good.ply";
  write_ply(file, bare(s.positions, s.polygons));
  const std::string good = read_file(file);

  Sample far = s;
  far.polygons[1].v[1] = 5;
  EXPECT_THROW(write_ply(file, bare(far.positions, far.polygons)), Error);
  Sample nan = s;
  nan.positions(1, 2) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(write_ply(file, bare(nan.positions, nan.polygons)), Error);
  Sample bad_normal = s;
  bad_normal.normals(0, 0) = std::numeric_limits<float>::infinity();
  PlyMesh bad_normals = bare(s.positions, s.polygons);
  bad_normals.normals = &bad_normal.normals;
  EXPECT_THROW(write_ply(file, bad_normals), Error);
  const Positions short_colours = s.colours.leftCols(4);
  EXPECT_THROW(write_ply(file, with_colours(bare(s.positions, s.polygons), short_colours)), Error);
  const std::vector<Vec2f> short_uvs(s.uvs.begin(), s.uvs.end() - 1);
  PlyMesh bad_uvs = bare(s.positions, s.polygons);
  bad_uvs.uvs = &short_uvs;
  EXPECT_THROW(write_ply(file, bad_uvs), Error);
  EXPECT_EQ(read_file(file), good);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);  // no temporary left beside it
}

}  // namespace facecap
