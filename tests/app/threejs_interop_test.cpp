// facecap's animated glTF read by three.js's own GLTFLoader, under node
// (tests/app/threejs/gltf_probe.mjs; setup.sh installs three.js beside it
// from npm): what a three.js app gets from `track --gltf`, the scene's
// objects, the animation's tracks, the morph targets by name, and the face
// where the tracker fitted it, seen through the file's camera with the
// AnimationMixer at a frame's time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "app/tracked_clip.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

bool have_threejs() {
  return test::run_command("command -v node >/dev/null 2>&1").code == 0 &&
         fs::exists(fs::path(FACECAP_THREEJS_DIR) / "node_modules" / "three" / "package.json");
}

// Skips the test where node or three.js is missing, or fails it under CI,
// where setup.sh installs them.
#define FACECAP_REQUIRE_THREEJS()                                                                       \
  if (!have_threejs()) {                                                                                \
    if (running_under_ci()) FAIL() << "node or three.js missing under CI (setup.sh installs them)";     \
    GTEST_SKIP() << "node or three.js not installed (setup.sh installs them): three.js is not checked"; \
  }

bool contains(const nlohmann::json& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

// Frames 3 and 17 of a 20-frame capture of `address_720p_a`, played by
// three.js at their times: the face part's inner landmark vertices (17-67),
// morphed by the influences the mixer set and placed by the face node's
// keyed transform, project through the glTF camera where frames.jsonl says
// the fit put them.
TEST(ThreeJsInterop, TheLoaderPlaysTheFaceWhereTheFitSawIt) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  FACECAP_REQUIRE_THREEJS();
  TempDir dir;
  const test::CommandResult tracked = test::track_20_frames(video, dir.path(), "--gltf");
  ASSERT_EQ(tracked.code, 0) << tracked.out;

  const std::vector<int> source = face_animation_source_vertices(*model)[0];
  std::string vertices;
  for (int i = 17; i < 68; ++i) {
    const auto at = std::find(source.begin(), source.end(), model->landmarks.vertices[size_t(i)]);
    ASSERT_NE(at, source.end()) << "landmark " << i;
    vertices += (vertices.empty() ? "" : ",") + std::to_string(at - source.begin());
  }
  const std::vector<std::string> rows = test::read_lines(dir.path() / "frames.csv");
  const int frames[2] = {3, 17};
  std::string times;
  for (const int frame : frames) times += (times.empty() ? "" : ",") + split_csv_line(rows.at(size_t(frame) + 1))[1];

  const fs::path report_path = dir.path() / "three.json";
  const test::CommandResult probed = test::run_command(
      "node " + (fs::path(FACECAP_THREEJS_DIR) / "gltf_probe.mjs").string() + " " +
      (dir.path() / "animation.glb").string() + " " + report_path.string() + " " + times + " " + vertices + " 2>&1");
  ASSERT_EQ(probed.code, 0) << probed.out;
  EXPECT_EQ(probed.out, "");  // nothing reported on the way
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);

  EXPECT_TRUE(contains(report["objects"], "PerspectiveCamera:camera")) << report["objects"];
  for (const char* track : {"face.position", "face.quaternion"})
    EXPECT_TRUE(contains(report["tracks"], track)) << report["tracks"];
  const nlohmann::json& targets = report["morph_targets"];
  ASSERT_EQ(targets.size(), size_t(model->num_expressions()) + 4);
  for (int j = 0; j < model->num_expressions(); ++j) EXPECT_EQ(targets[size_t(j)], model->expression_names[size_t(j)]);
  EXPECT_EQ(targets.back(), "eyesTurnDown");
  EXPECT_TRUE(contains(report["images"], kFaceMatteImageName));
  EXPECT_NEAR(double(report["camera"]["aspect"]), 1280.0 / 720.0, 1e-9);

  double worst = 0;
  for (int k = 0; k < 2; ++k) {
    const std::vector<cv::Point2f> fitted = test::fitted_landmarks(dir.path() / "frames.jsonl", frames[k], 1.0f);
    const nlohmann::json& ndc = report["ndc"][size_t(k)];
    ASSERT_EQ(ndc.size(), 51u);
    for (size_t i = 0; i < 51; ++i) {
      // Normalised device coordinates to pixels, with facecap's principal
      // point at (W / 2, H / 2) in pixel-centre coordinates: half a pixel
      // right of and below the frame's centre, where three.js's camera puts it.
      const cv::Point2f p(float((double(ndc[i][0]) + 1) / 2 * 1280), float((1 - double(ndc[i][1])) / 2 * 720));
      worst = std::max(worst, double(cv::norm(p - fitted[17 + i])));
    }
  }
  std::printf("inner landmarks played by three.js: at most %.4f px from the fit's\n", worst);
  EXPECT_LT(worst, 0.02);
}

}  // namespace facecap
