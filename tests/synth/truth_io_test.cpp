#include "facecap/synth/truth_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

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

}  // namespace facecap
