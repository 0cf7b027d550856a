#include "facecap/io/gltf_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "io/glb_reader.hpp"

namespace facecap {

namespace {

// A unit square of two triangles with two morph targets and three keys.
GltfAnimatedMesh square() {
  GltfAnimatedMesh m;
  m.name = "square";
  GltfPrimitive p;
  p.name = "square";
  p.positions.resize(3, 4);
  p.positions << 0, 1, 1, 0,  //
      0, 0, 1, 1,             //
      0, 0, 0, 0;
  p.normals = Positions::Zero(3, 4);
  p.normals.row(2).setOnes();
  p.uvs.resize(2, 4);
  p.uvs << 0, 1, 1, 0, 1, 1, 0, 0;
  p.triangles = {{0, 1, 2}, {0, 2, 3}};
  p.morph_targets = {Positions::Zero(3, 4), Positions::Zero(3, 4)};
  p.morph_targets[0](2, 2) = 0.5f;
  p.morph_targets[1](0, 1) = -0.25f;
  m.primitives.push_back(p);
  m.morph_target_names = {"lift", "squeeze"};
  m.times = {0.0f, 0.5f, 1.0f};
  m.translations = {Eigen::Vector3f(0, 0, -1), Eigen::Vector3f(0.1f, 0, -1), Eigen::Vector3f(0.2f, 0, -1)};
  m.rotations = {Eigen::Quaternionf::Identity(), Eigen::Quaternionf(Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitY())),
                 Eigen::Quaternionf(Eigen::AngleAxisf(0.6f, Eigen::Vector3f::UnitY()))};
  m.weights.resize(2, 3);
  m.weights << 0.0f, 0.5f, 1.0f,  //
      0.25f, 0.0f, 0.75f;
  m.camera = GltfCamera{0.7, 1.5, 0.01};
  m.asset_extras = {{"note", "test"}};
  return m;
}

}  // namespace

TEST(GltfWriter, WritesAGlbWhoseAccessorsReadBackAsGiven) {
  TempDir dir;
  const GltfAnimatedMesh m = square();
  write_glb(dir.path() / "square.glb", m);
  const test::Glb g = test::Glb::read(dir.path() / "square.glb");
  EXPECT_EQ(g.doc["asset"]["version"], "2.0");
  EXPECT_EQ(g.doc["asset"]["extras"]["note"], "test");

  const auto& prim = g.doc["meshes"][0]["primitives"][0];
  const auto& position = g.doc["accessors"][int(prim["attributes"]["POSITION"])];
  EXPECT_EQ(position["count"], 4);
  EXPECT_EQ(position["min"], nlohmann::json({0.0, 0.0, 0.0}));  // required by the specification
  EXPECT_EQ(position["max"], nlohmann::json({1.0, 1.0, 0.0}));
  const std::vector<float> p = g.floats(prim["attributes"]["POSITION"]);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(p[i * 3 + c], m.primitives[0].positions(c, i));
  EXPECT_EQ(g.indices(prim["indices"]), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(g.floats(prim["attributes"]["TEXCOORD_0"]).size(), 8u);
  EXPECT_EQ(g.floats(prim["attributes"]["NORMAL"]).size(), 12u);

  // Morph targets: offsets, names and bounds.
  ASSERT_EQ(prim["targets"].size(), 2u);
  const std::vector<float> lift = g.floats(prim["targets"][0]["POSITION"]);
  ASSERT_EQ(lift.size(), 12u);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(lift[k], k == 2 * 3 + 2 ? 0.5f : 0.0f) << k;
  // One vertex of four moves: stored sparse, the others zero.
  EXPECT_EQ(g.doc["accessors"][int(prim["targets"][0]["POSITION"])]["sparse"]["count"], 1);
  EXPECT_EQ(g.doc["accessors"][int(prim["targets"][0]["POSITION"])]["max"], nlohmann::json({0.0, 0.0, 0.5}));
  EXPECT_EQ(g.doc["accessors"][int(prim["targets"][1]["POSITION"])]["min"][0], -0.25);
  EXPECT_EQ(g.doc["meshes"][0]["extras"]["targetNames"], nlohmann::json({"lift", "squeeze"}));
  EXPECT_EQ(g.doc["meshes"][0]["weights"].size(), 2u);

  // The animation: one sampler per animated property, keyed at the times.
  const auto& anim = g.doc["animations"][0];
  ASSERT_EQ(anim["channels"].size(), 3u);
  std::map<std::string, int> output;
  for (const auto& ch : anim["channels"]) {
    EXPECT_EQ(ch["target"]["node"], 0);
    const auto& s = anim["samplers"][int(ch["sampler"])];
    EXPECT_EQ(g.floats(s["input"]), m.times);
    EXPECT_EQ(g.doc["accessors"][int(s["input"])]["max"][0], 1.0);
    output[ch["target"]["path"]] = s["output"];
  }
  const std::vector<float> w = g.floats(output.at("weights"));
  ASSERT_EQ(w.size(), 6u);  // keys x targets, each key's targets together
  EXPECT_EQ(w[1 * 2 + 0], 0.5f);
  EXPECT_EQ(w[2 * 2 + 1], 0.75f);
  const std::vector<float> r = g.floats(output.at("rotation"));
  ASSERT_EQ(r.size(), 12u);
  EXPECT_NEAR(r[1 * 4 + 1], std::sin(0.15f), 1e-6);  // x, y, z, w
  EXPECT_NEAR(r[1 * 4 + 3], std::cos(0.15f), 1e-6);
  EXPECT_EQ(g.floats(output.at("translation"))[2 * 3 + 0], 0.2f);

  // The node starts at the first key; the camera is a second root node.
  EXPECT_EQ(g.doc["nodes"][0]["translation"], nlohmann::json({0.0, 0.0, -1.0}));
  EXPECT_EQ(g.doc["cameras"][0]["perspective"]["yfov"], 0.7);
  EXPECT_EQ(g.doc["nodes"][1]["camera"], 0);
  EXPECT_EQ(g.doc["scenes"][0]["nodes"], nlohmann::json({0, 1}));
  // Every buffer view is 4-byte aligned and inside the buffer.
  for (const auto& v : g.doc["bufferViews"]) {
    EXPECT_EQ(int(v["byteOffset"]) % 4, 0);
    EXPECT_LE(size_t(v["byteOffset"]) + size_t(v["byteLength"]), g.bin.size());
  }
}

TEST(GltfWriter, EmbedsTheTextureImage) {
  TempDir dir;
  GltfAnimatedMesh m = square();
  m.primitives[0].base_colour_png = {0x89, 'P', 'N', 'G', 1, 2, 3};
  write_glb(dir.path() / "t.glb", m);
  const test::Glb g = test::Glb::read(dir.path() / "t.glb");
  const auto& image = g.doc["images"][0];
  EXPECT_EQ(image["mimeType"], "image/png");
  const auto& view = g.doc["bufferViews"][int(image["bufferView"])];
  EXPECT_EQ(g.bin.substr(size_t(view["byteOffset"]), 7), std::string("\x89PNG\x01\x02\x03", 7));
  EXPECT_EQ(g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
}

TEST(GltfWriter, EachPartHasItsMaterialAndTheMeshsTargets) {
  TempDir dir;
  GltfAnimatedMesh m = square();
  GltfPrimitive second = m.primitives[0];
  second.name = "second";
  second.uvs.resize(2, 0);
  second.colours = Positions::Constant(3, 4, 0.5f);
  second.base_colour = Eigen::Vector3f(1.0f, 0.5f, 0.25f);
  m.primitives.push_back(second);
  write_glb(dir.path() / "two.glb", m);
  const test::Glb g = test::Glb::read(dir.path() / "two.glb");
  const auto& prims = g.doc["meshes"][0]["primitives"];
  ASSERT_EQ(prims.size(), 2u);
  EXPECT_EQ(prims[1]["targets"].size(), 2u);
  EXPECT_EQ(prims[1]["material"], 1);
  EXPECT_FALSE(prims[1]["attributes"].contains("TEXCOORD_0"));
  EXPECT_EQ(g.floats(prims[1]["attributes"]["COLOR_0"]), std::vector<float>(12, 0.5f));
  EXPECT_EQ(g.doc["materials"][1]["name"], "second");
  EXPECT_EQ(g.doc["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"], nlohmann::json({1.0, 0.5, 0.25, 1.0}));
}

TEST(GltfWriter, AStaticMeshHasNoAnimation) {
  TempDir dir;
  GltfAnimatedMesh m = square();
  m.times.clear();
  m.translations.clear();
  m.rotations.clear();
  m.weights.resize(2, 0);
  write_glb(dir.path() / "s.glb", m);
  const test::Glb g = test::Glb::read(dir.path() / "s.glb");
  EXPECT_FALSE(g.doc.contains("animations"));
}

TEST(GltfWriter, InconsistentInputIsAnErrorAndLeavesTheOldFile) {
  TempDir dir;
  const auto path = dir.path() / "keep.glb";
  write_glb(path, square());
  const auto size = std::filesystem::file_size(path);
  auto expect_rejected = [&](GltfAnimatedMesh m, const char* what) {
    EXPECT_THROW(write_glb(path, m), Error) << what;
    EXPECT_EQ(std::filesystem::file_size(path), size) << what;
  };
  GltfAnimatedMesh m = square();
  m.times[2] = 0.5f;
  expect_rejected(m, "times not increasing");
  m = square();
  m.primitives[0].positions(1, 2) = std::nanf("");
  expect_rejected(m, "NaN position");
  m = square();
  m.weights(0, 1) = std::numeric_limits<float>::infinity();
  expect_rejected(m, "infinite weight");
  m = square();
  m.primitives[0].triangles.push_back({0, 1, 4});
  expect_rejected(m, "index out of range");
  m = square();
  m.morph_target_names.pop_back();
  expect_rejected(m, "names missing");
  m = square();
  m.primitives.push_back(m.primitives[0]);
  m.primitives[1].morph_targets.pop_back();
  expect_rejected(m, "a part lacks a target");
  m = square();
  m.rotations.pop_back();
  expect_rejected(m, "keys missing");
  m = square();
  m.primitives[0].uvs.resize(2, 3);
  expect_rejected(m, "UVs short");
  m = square();
  m.images.push_back({"face_matte", {}});
  expect_rejected(m, "an image with no bytes");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);  // no temporaries left
}

}  // namespace facecap
