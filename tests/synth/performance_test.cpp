#include "facecap/synth/performance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "facecap/core/error.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(SynthPerformance, SameSeedSameParameters) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 20;
  o.seed = 5;
  const SynthPerformance a = make_performance(*model, o), b = make_performance(*model, o);
  EXPECT_TRUE(a.identity.isApprox(b.identity));
  EXPECT_TRUE(a.frames[13].expression.isApprox(b.frames[13].expression));
  o.seed = 6;
  EXPECT_FALSE(a.identity.isApprox(make_performance(*model, o).identity));
}

TEST(SynthPerformance, WeightsPoseAndLightingStayInRange) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 120;  // one full yaw sweep
  const SynthPerformance p = make_performance(*model, o);
  EXPECT_EQ(p.identity.head(50).cwiseAbs().maxCoeff() > 0.3f, true);
  EXPECT_EQ(p.identity.tail(50).cwiseAbs().maxCoeff(), 0.0f);
  double min_yaw = 1e9, max_yaw = -1e9, max_jaw = 0, gaze_spread = 0;
  const int jaw = model->expression_index("jawOpen");
  for (const SynthFrame& f : p.frames) {
    EXPECT_GE(f.expression.minCoeff(), 0.0f);
    EXPECT_LE(f.expression.maxCoeff(), 1.0f);
    const double yaw = yaw_pitch_roll_deg(f.pose.rotation_matrix()).x();
    min_yaw = std::min(min_yaw, yaw);
    max_yaw = std::max(max_yaw, yaw);
    max_jaw = std::max(max_jaw, double(f.expression[jaw]));
    EXPECT_GT(sh_shade(f.lighting, 0.0, 0.0, 1.0), 0.3);
    EXPECT_LE(std::abs(f.gaze_deg.x()), 30.0);
    EXPECT_LE(std::abs(f.gaze_deg.y()), 20.0);
    gaze_spread = std::max(gaze_spread, (f.gaze_deg - p.frames[0].gaze_deg).norm());
  }
  EXPECT_GT(gaze_spread, 5.0);  // the eyes wander
  EXPECT_LT(min_yaw, -27.0);
  EXPECT_GT(max_yaw, 27.0);
  EXPECT_GT(max_jaw, 0.2);  // it talks
}

TEST(SynthPerformance, StillModeHoldsEverything) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 10;
  o.still = true;
  const SynthPerformance p = make_performance(*model, o);
  for (const SynthFrame& f : p.frames) {
    EXPECT_TRUE(f.pose.rotation.isApprox(p.frames[0].pose.rotation));
    EXPECT_TRUE(f.pose.translation.isApprox(p.frames[0].pose.translation));
    EXPECT_EQ(f.expression.maxCoeff(), 0.0f);
    EXPECT_EQ(f.gaze_deg, Vec2d::Zero());
  }
}

TEST(SynthPerformance, BadOptionsAreRejectedByName) {
  SynthOptions o;
  o.frames = 0;
  try {
    o.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos);
  }
  o = SynthOptions{};
  o.width = 10;
  EXPECT_THROW(o.check(), Error);
  o = SynthOptions{};
  o.render_frames = o.frames + 1;  // more than the performance has
  EXPECT_THROW(o.check(), Error);
  o.render_frames = -1;
  EXPECT_THROW(o.check(), Error);
  for (const double roll : {-181.0, 200.0, std::nan("")}) {
    o = SynthOptions{};
    o.camera_roll_deg = roll;
    try {
      o.check();
      FAIL() << roll;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--roll"), std::string::npos);
    }
  }
  // A face texture must be a square colour texture of floats.
  for (const cv::Mat& bad : {cv::Mat(64, 32, CV_32FC3), cv::Mat(64, 64, CV_8UC3), cv::Mat(8, 8, CV_32FC3)}) {
    o = SynthOptions{};
    o.face_texture = bad;
    EXPECT_THROW(o.check(), Error);
  }
  o.face_texture = cv::Mat(64, 64, CV_32FC3, cv::Scalar::all(0.5));
  EXPECT_NO_THROW(o.check());
}

}  // namespace facecap
