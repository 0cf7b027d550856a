#include "facecap/detect/landmarks.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/pipeline/landmark_eval.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(Landmarks, NmeIsMeanErrorOverOuterEyeDistance) {
  Landmarks truth = zero_landmarks();
  for (int i = 0; i < kNumLandmarks; ++i) truth[i] = Vec2f(float(i), 0.0f);
  truth[36] = Vec2f(0, 0);
  truth[45] = Vec2f(50, 0);
  Landmarks shifted = truth;
  for (auto& p : shifted) p += Vec2f(0, 2.0f);
  EXPECT_NEAR(landmark_nme(shifted, truth), 2.0f / 50.0f, 1e-6f);
}

TEST(Landmarks, ReadsPtsAsZeroBased) {
  FACECAP_REQUIRE_DATA(pts, "lfpw_image_0010.pts");
  const Landmarks lm = read_pts(pts);
  // First line of the file: 611.284152 272.773913 (1-based).
  EXPECT_NEAR(lm[0].x(), 610.284152f, 1e-3f);
  EXPECT_NEAR(lm[0].y(), 271.773913f, 1e-3f);
}

TEST(Landmarks, MalformedPtsIsAnError) {
  TempDir dir;
  std::ofstream(dir.path() / "bad.pts") << "version: 1\nn_points: 68\n{\n1 2\n}\n";
  EXPECT_THROW(read_pts(dir.path() / "bad.pts"), Error);
  EXPECT_THROW(read_pts(dir.path() / "missing.pts"), Error);
}

TEST(LandmarkEval, DlibMeetsTheBarOnTheAnnotatedLfpwImage) {
  FACECAP_REQUIRE_DATA(image, "lfpw_image_0010.png");
  FACECAP_REQUIRE_DATA(pts, "lfpw_image_0010.pts");
  const LandmarkEvalResult r = evaluate_landmarks(image, pts);
  EXPECT_GE(r.faces, 1);
  EXPECT_LE(r.nme, 0.035f);
  EXPECT_GT(r.nme, 0.0f);
}

}  // namespace facecap
