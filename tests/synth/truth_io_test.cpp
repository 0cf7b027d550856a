#include "facecap/synth/truth_io.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(TruthIo, RoundTripsEveryFrameParameter) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 4;
  o.detail = true;
  SynthTruth t;
  t.performance = make_performance(*model, o);
  t.performance.frames[2].gaze_deg = Vec2d(12.5, -4.25);
  t.expression_names = model->expression_names;
  for (int f = 0; f < 4; ++f) {
    Landmarks lm = zero_landmarks();
    lm[5] = Vec2f(float(f), 2.5f);
    t.landmarks.push_back(lm);
    t.vertex_landmarks.push_back(lm);
  }
  TempDir dir;
  write_truth(dir.path() / "truth.json", t);
  const SynthTruth r = read_truth(dir.path() / "truth.json");
  EXPECT_EQ(r.performance.options.frames, 4);
  EXPECT_TRUE(r.performance.options.detail);
  EXPECT_DOUBLE_EQ(r.performance.camera.focal, t.performance.camera.focal);
  EXPECT_TRUE(r.performance.identity.isApprox(t.performance.identity));
  EXPECT_TRUE(r.performance.frames[3].expression.isApprox(t.performance.frames[3].expression));
  EXPECT_TRUE(r.performance.frames[2].pose.rotation.isApprox(t.performance.frames[2].pose.rotation));
  EXPECT_TRUE(r.performance.frames[1].lighting.isApprox(t.performance.frames[1].lighting));
  EXPECT_EQ(r.performance.frames[2].gaze_deg, Vec2d(12.5, -4.25));
  EXPECT_EQ(r.landmarks[3][5], Vec2f(3.0f, 2.5f));
  EXPECT_EQ(r.expression_names, model->expression_names);
}

TEST(TruthIo, MalformedFilesAreNamed) {
  TempDir dir;
  std::ofstream(dir.path() / "bad.json") << "{\"format\": \"something else\"}";
  try {
    read_truth(dir.path() / "bad.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos);
  }
  EXPECT_THROW(read_truth(dir.path() / "none.json"), Error);
}

TEST(TruthIo, AGazeOfOtherThanTwoAnglesIsNamedAndAMissingOneIsStraightAhead) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 2;
  SynthTruth t;
  t.performance = make_performance(*model, o);
  t.expression_names = model->expression_names;
  t.landmarks.assign(2, zero_landmarks());
  t.vertex_landmarks.assign(2, zero_landmarks());
  TempDir dir;
  write_truth(dir.path() / "truth.json", t);
  std::ifstream in(dir.path() / "truth.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["frames"][0].erase("gaze_yaw_pitch_deg");  // a truth file from before gaze
  j["frames"][1]["gaze_yaw_pitch_deg"] = {1.0};
  std::ofstream(dir.path() / "edited.json") << j.dump();
  try {
    read_truth(dir.path() / "edited.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("edited.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gaze"), std::string::npos);
  }
  j["frames"][1].erase("gaze_yaw_pitch_deg");
  std::ofstream(dir.path() / "old.json") << j.dump();
  const SynthTruth r = read_truth(dir.path() / "old.json");
  EXPECT_EQ(r.performance.frames[0].gaze_deg, Vec2d::Zero());
}

}  // namespace facecap
