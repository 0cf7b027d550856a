// A texture's halvings, the level a view needs, and where a level-0 texel
// lies on each level.
#include "facecap/render/texture_levels.hpp"

#include <gtest/gtest.h>

#include "swap/unit_square.hpp"

namespace facecap {

namespace {

// A ramp: each texel holds its own column (channel 0) and row (channel 1).
cv::Mat ramp(int size) {
  cv::Mat t(size, size, CV_32FC2);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) t.at<cv::Vec2f>(y, x) = {float(x), float(y)};
  return t;
}

}  // namespace

TEST(TextureLevels, HalvesDownToTheSmallestSizeAndPicksTheLevelOfDetailAViewNeeds) {
  const TextureLevels levels(ramp(1024), 64);
  ASSERT_EQ(levels.count(), 5);  // 1024, 512, 256, 128, 64
  EXPECT_EQ(levels.level(4).size(), cv::Size(64, 64));
  EXPECT_EQ(levels.lod_for(0.5f), 0.0f);  // magnified: the finest
  EXPECT_EQ(levels.lod_for(2.0f), 1.0f);  // two texels a pixel: every second one
  EXPECT_NEAR(levels.lod_for(3.0f), 1.585f, 1e-3f);
  EXPECT_EQ(levels.lod_for(1e6f), 4.0f);  // no coarser level than the last
  EXPECT_EQ(levels.lod_for(std::nanf("")), 0.0f);
  EXPECT_TRUE(TextureLevels().empty());
  EXPECT_EQ(TextureLevels(ramp(48), 64).count(), 1);
}

// The box filter keeps a ramp's values: a level read where to_level() puts
// a level-0 point gives that point's own column and row.
TEST(TextureLevels, ALevelReadAtAPointGivesWhatLevelZeroHasThere) {
  const TextureLevels levels(ramp(256), 16);
  for (int k = 0; k < levels.count(); ++k) {
    for (const float c0 : {20.0f, 100.25f, 200.5f}) {
      const float x = levels.to_level(k, c0, false), y = levels.to_level(k, c0 + 10.0f, true);
      const cv::Mat& l = levels.level(k);
      const int x0 = int(x), y0 = int(y);
      const float fx = x - x0, fy = y - y0;
      auto at = [&](int r, int c) { return l.at<cv::Vec2f>(r, c); };
      const cv::Vec2f v = (at(y0, x0) * (1 - fx) + at(y0, x0 + 1) * fx) * (1 - fy) +
                          (at(y0 + 1, x0) * (1 - fx) + at(y0 + 1, x0 + 1) * fx) * fy;
      EXPECT_NEAR(v[0], c0, 1e-3f) << k;
      EXPECT_NEAR(v[1], c0 + 10.0f, 1e-3f) << k;
    }
  }
}

// Between two levels the two are blended: a checkerboard's white texel
// (level 0: 1) is grey on level 1 (0.5), and three quarters white half way.
TEST(TextureLevels, BetweenTwoLevelsTheirReadsAreBlended) {
  cv::Mat board(64, 64, CV_32F);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) board.at<float>(y, x) = float((x + y) % 2);
  const TextureLevels levels(board, 8);
  EXPECT_FLOAT_EQ(levels.sample<1>(0.0f, 11, 10)[0], 1.0f);
  EXPECT_FLOAT_EQ(levels.sample<1>(1.0f, 11, 10)[0], 0.5f);
  EXPECT_FLOAT_EQ(levels.sample<1>(0.5f, 11, 10)[0], 0.75f);
  EXPECT_FLOAT_EQ(levels.sample<1>(0.5f, 10, 10)[0], 0.25f);
}

// Asking for a read ahead changes nothing, anywhere: inside, at the
// borders, beyond them (clamped as the reads are) and past the last level.
TEST(TextureLevels, AskingForAReadAheadChangesNothingAnywhere) {
  const TextureLevels levels(ramp(256), 16);
  const cv::Vec2f before = levels.sample<2>(1.5f, 100.25f, 30.5f);
  for (const float lod : {0.0f, 0.5f, 1.5f, 4.0f, 9.0f})
    for (const float c : {-1e6f, -3.0f, 0.0f, 100.25f, 255.0f, 255.9f, 1e6f}) levels.prefetch(lod, c, 255.0f - c);
  EXPECT_EQ(levels.sample<2>(1.5f, 100.25f, 30.5f), before);
  EXPECT_NEAR(before[0], 100.25f, 1e-3f);
}

// A square 12.8 cm across, 60 cm from a camera of focal 800 px, spans
// 170.7 px; its UVs the whole of a 1024-texel texture: 6 texels a pixel.
TEST(TextureLevels, TexelsPerPixelOfASquareFacingTheCamera) {
  TriangleMesh square = test::unit_square();
  Positions points(3, 4);
  points.col(0) = Vec3f(-6.4f, 6.4f, 60.0f);
  points.col(1) = Vec3f(6.4f, 6.4f, 60.0f);
  points.col(2) = Vec3f(6.4f, -6.4f, 60.0f);
  points.col(3) = Vec3f(-6.4f, -6.4f, 60.0f);
  const PinholeCamera camera = PinholeCamera::centered(800.0, 640, 480);
  EXPECT_NEAR(texels_per_pixel(square, points, camera, 1024), 1024.0f / (12.8f * 800.0f / 60.0f), 1e-3f);
  // Twice as far: twice as many texels a pixel.
  points.row(2).setConstant(120.0f);
  EXPECT_NEAR(texels_per_pixel(square, points, camera, 1024), 2.0f * 1024.0f / (12.8f * 800.0f / 60.0f), 1e-3f);
  // Turned away from the camera: none seen.
  for (Triangle& t : square.triangles) std::swap(t[1], t[2]);
  for (Triangle& t : square.triangle_uvs) std::swap(t[1], t[2]);
  EXPECT_EQ(texels_per_pixel(square, points, camera, 1024), 1.0f);
}

}  // namespace facecap
