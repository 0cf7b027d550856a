#include "facecap/model/ict_loader.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A copy of the model folder made of symlinks, so one file can be damaged.
void link_model(const fs::path& from, const fs::path& to) {
  for (const auto& e : fs::directory_iterator(from)) fs::create_symlink(e.path(), to / e.path().filename());
}

std::string load_error(const fs::path& dir) {
  try {
    load_ict_model(dir, {.num_identity = 2});
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(IctLoader, LoadsTheIctFaceModelLight) {
  FACECAP_REQUIRE_MODEL(model);
  EXPECT_EQ(model->num_vertices, 26719);
  EXPECT_EQ(model->polygons.size(), 26384u);
  EXPECT_EQ(model->uvs.size(), 28911u);
  EXPECT_EQ(model->num_identity(), 100);
  EXPECT_EQ(model->num_expressions(), 53);
  EXPECT_EQ(model->expression_names.front(), "browDown_L");
  EXPECT_GE(model->expression_index("jawOpen"), 0);
  EXPECT_EQ(model->landmarks.vertices.size(), 68u);
  EXPECT_EQ(model->landmarks.vertices[30], 4857);  // nose tip
  int triangles = 0;
  for (const Polygon& p : model->polygons) triangles += p.size() == 3;
  EXPECT_EQ(triangles, 548);
  // FACTS.md: outer eye corners 8.92 cm apart, units are centimetres.
  const Eigen::Map<const Positions> v(model->neutral.data(), 3, model->num_vertices);
  const float eyes = (v.col(model->landmarks.vertices[36]) - v.col(model->landmarks.vertices[45])).norm();
  EXPECT_NEAR(eyes, 8.92f, 0.01f);
  EXPECT_TRUE(model->identity_basis.allFinite());
  EXPECT_TRUE(model->expression_basis.allFinite());
}

TEST(IctLoader, MissingFolderSaysWhereToGetTheModel) {
  const std::string e = load_error("/nonexistent/ict");
  EXPECT_NE(e.find("not found"), std::string::npos);
  EXPECT_NE(e.find("FACECAP_MODEL_DIR"), std::string::npos);
}

TEST(IctLoader, MissingExpressionNamesTheFile) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  link_model(default_model_dir(), dir.path());
  fs::remove(dir.path() / "jawOpen.obj.gz");
  const std::string e = load_error(dir.path());
  EXPECT_NE(e.find("jawOpen"), std::string::npos) << e;
}

TEST(IctLoader, WrongVertexCountNamesTheFile) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  link_model(default_model_dir(), dir.path());
  fs::remove(dir.path() / "mouthClose.obj.gz");
  std::ofstream(dir.path() / "mouthClose.obj") << "v 0 0 0\nv 1 1 1\n";
  const std::string e = load_error(dir.path());
  EXPECT_NE(e.find("mouthClose.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("expected 26719"), std::string::npos) << e;
}

TEST(IctLoader, TruncatedNeutralNamesTheFile) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  link_model(default_model_dir(), dir.path());
  const fs::path neutral = dir.path() / "generic_neutral_mesh.obj.gz";
  const fs::path source = fs::read_symlink(neutral);
  fs::remove(neutral);
  std::ifstream in(source, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(neutral, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  const std::string e = load_error(dir.path());
  EXPECT_NE(e.find("generic_neutral_mesh.obj.gz"), std::string::npos) << e;
}

TEST(IctLoader, NanInABlendshapeIsAnError) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  link_model(default_model_dir(), dir.path());
  fs::remove(dir.path() / "identity001.obj.gz");
  std::ofstream(dir.path() / "identity001.obj") << "v 0 nan 0\n";
  const std::string e = load_error(dir.path());
  EXPECT_NE(e.find("identity001.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("non-finite"), std::string::npos) << e;
}

}  // namespace facecap
