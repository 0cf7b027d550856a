#include "facecap/io/mesh_writer.hpp"

#include <gtest/gtest.h>

#include <random>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/model/obj_reader.hpp"
#include "test_support.hpp"

namespace facecap {

using test::read_file;

// The records, exactly: the comment, fixed-point coordinates (5 decimals,
// 10 um in cm), UVs (6 decimals), 1-based v/vt corners, quads kept.
TEST(MeshWriter, WritesTheObjRecordsExactly) {
  Positions p(3, 5);
  p << 0.0f, 1.0f, 1.0f, 0.0f, -2.5f,     //
      0.0f, 0.0f, 1.0f, 1.0f, 0.000004f,  //
      10.123456f, -0.5f, 0.0f, 0.0f, 123.45678f;
  const std::vector<Vec2f> uvs = {{0, 0}, {1, 0}, {1, 1}, {0.25f, 0.125f}};
  Polygon quad, tri;
  quad.v = {0, 1, 2, 3};
  quad.uv = {0, 1, 2, 3};
  tri.v = {2, 4, 3, -1};
  tri.uv = {2, 0, 3, -1};
  const std::vector<Polygon> polygons = {quad, tri};
  TempDir dir;
  write_obj(dir.path() / "a.obj",
            {.positions = &p, .polygons = &polygons, .uvs = &uvs, .comment = "first line\nsecond"});
  EXPECT_EQ(read_file(dir.path() / "a.obj"),
            "# first line\n# second\n"
            "v 0.00000 0.00000 10.12346\nv 1.00000 0.00000 -0.50000\nv 1.00000 1.00000 0.00000\n"
            "v 0.00000 1.00000 0.00000\nv -2.50000 0.00000 123.45678\n"
            "vt 0.000000 0.000000\nvt 1.000000 0.000000\nvt 1.000000 1.000000\nvt 0.250000 0.125000\n"
            "f 1/1 2/2 3/3 4/4\nf 3/3 5/1 4/4\n");
  write_obj(dir.path() / "b.obj", {.positions = &p, .polygons = &polygons});
  EXPECT_NE(read_file(dir.path() / "b.obj").find("\nf 1 2 3 4\nf 3 5 4\n"), std::string::npos);
}

// A material: the library named before the vertices, the material before
// the faces; the library a diffuse material with its texture.
TEST(MeshWriter, AnObjNamesItsMaterialAndTheLibraryItsTexture) {
  Positions p(3, 3);
  p << 0, 1, 0,  //
      0, 0, 1,   //
      0, 0, 0;
  Polygon tri;
  tri.v = {0, 1, 2, -1};
  tri.uv = {0, 1, 2, -1};
  const std::vector<Polygon> polygons = {tri};
  const std::vector<Vec2f> uvs = {{0, 0}, {1, 0}, {0, 1}};
  TempDir dir;
  write_obj(dir.path() / "a.obj", {.positions = &p,
                                   .polygons = &polygons,
                                   .uvs = &uvs,
                                   .comment = "c",
                                   .material_library = "face.mtl",
                                   .material = "face"});
  EXPECT_EQ(read_file(dir.path() / "a.obj"),
            "# c\nmtllib face.mtl\n"
            "v 0.00000 0.00000 0.00000\nv 1.00000 0.00000 0.00000\nv 0.00000 1.00000 0.00000\n"
            "vt 0.000000 0.000000\nvt 1.000000 0.000000\nvt 0.000000 1.000000\n"
            "usemtl face\nf 1/1 2/2 3/3\n");
  write_mtl(dir.path() / "face.mtl", "face", "../albedo.png", "one\ntwo");
  EXPECT_EQ(read_file(dir.path() / "face.mtl"),
            "# one\n# two\nnewmtl face\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\nmap_Kd ../albedo.png\n");
  write_mtl(dir.path() / "plain.mtl", "face", "", "");
  EXPECT_EQ(read_file(dir.path() / "plain.mtl").find("map_Kd"), std::string::npos);
}

// A refined frame's size read back by the model's OBJ reader.
TEST(MeshWriter, ALargeMeshReadsBackWithinTheWrittenPrecision) {
  constexpr int kVertices = 20000;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-30.0f, 30.0f), unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> vertex(0, kVertices - 1);
  Positions p(3, kVertices);
  std::vector<Vec2f> uvs(kVertices);
  for (int i = 0; i < kVertices; ++i) {
    p.col(i) = Vec3f(coordinate(rng), coordinate(rng), coordinate(rng));
    uvs[size_t(i)] = Vec2f(unit(rng), unit(rng));
  }
  std::vector<Polygon> polygons(40000);
  for (Polygon& poly : polygons)
    for (int k = 0; k < 3; ++k) poly.v[k] = poly.uv[k] = vertex(rng);
  TempDir dir;
  write_obj(dir.path() / "big.obj", {.positions = &p, .polygons = &polygons, .uvs = &uvs, .comment = "big"});
  const ObjData back = read_obj(dir.path() / "big.obj");
  ASSERT_EQ(back.num_vertices(), kVertices);
  ASSERT_EQ(back.uvs.size(), uvs.size());
  ASSERT_EQ(back.polygons.size(), polygons.size());
  double worst = 0, worst_uv = 0;
  for (int i = 0; i < kVertices; ++i) {
    for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(back.positions[3 * i + k] - p(k, i))));
    worst_uv = std::max(worst_uv, double((back.uvs[size_t(i)] - uvs[size_t(i)]).cwiseAbs().maxCoeff()));
  }
  EXPECT_LE(worst, 0.5e-5 + 4e-6);  // half the last decimal, plus float rounding at 30
  EXPECT_LE(worst_uv, 0.5e-6 + 1e-7);
  for (size_t t = 0; t < polygons.size(); ++t) {
    EXPECT_EQ(back.polygons[t].v, polygons[t].v) << t;
    EXPECT_EQ(back.polygons[t].uv, polygons[t].uv) << t;
  }
}

TEST(MeshWriter, AnUnwritablePathIsAClearErrorAndNoFile) {
  Positions p = Positions::Zero(3, 3);
  Polygon tri;
  tri.v = {0, 1, 2, -1};
  const std::vector<Polygon> polygons = {tri};
  EXPECT_THROW(write_obj("/proc/facecap-no-such-dir/a.obj", {.positions = &p, .polygons = &polygons}), Error);
  TempDir dir;
  Polygon bad = tri;
  bad.v[2] = 7;  // no such vertex
  const std::vector<Polygon> broken = {bad};
  EXPECT_THROW(write_obj(dir.path() / "a.obj", {.positions = &p, .polygons = &broken}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "a.obj"));
}

}  // namespace facecap
