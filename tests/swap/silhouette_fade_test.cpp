#include "facecap/swap/silhouette_fade.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace facecap {

TEST(SilhouetteFade, TurnedAwaySurfaceFadesOnlyNearTheOutline) {
  const SilhouetteFade fade{0.3f, 10.0f};
  const auto alpha = [&](float facing, float outline_px) { return fade.alpha(fade.turned(facing), outline_px); };
  // Facing the camera: opaque anywhere.
  for (float d : {0.0f, 5.0f, 15.0f, 40.0f}) EXPECT_FLOAT_EQ(alpha(1.0f, d), 1.0f) << d;
  // Grazing (below the start), at the outline and within the band: clear.
  EXPECT_FLOAT_EQ(alpha(0.1f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(alpha(0.1f, 10.0f), 0.0f);
  // Past the band it eases off, and from twice the band the surface stays
  // opaque however it turns (the underside of the nose).
  EXPECT_NEAR(alpha(0.1f, 15.0f), 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(alpha(0.1f, 20.0f), 1.0f);
  EXPECT_FLOAT_EQ(alpha(-0.5f, 60.0f), 1.0f);
  // Within the band, the smooth step from the start over the next 0.3.
  EXPECT_NEAR(alpha(0.45f, 0.0f), 0.5f, 1e-6f);
  EXPECT_LT(alpha(0.35f, 0.0f), alpha(0.45f, 0.0f));
  EXPECT_FLOAT_EQ(alpha(0.6f, 0.0f), 1.0f);
}

// Inside the outline, a dark strip of surface turned away (the underside of
// a nose seen from below) takes the colour of the skin around it that faces
// the camera; near the outline, and where the surface faces the camera,
// the render is left as it is.
TEST(SilhouetteFade, ATurnedAwayStripInsideTakesTheColourAroundIt) {
  const SilhouetteFade fade{0.3f, 8.0f};
  cv::Mat render(80, 80, CV_32FC3, cv::Scalar(200, 150, 120));
  cv::Mat turned(80, 80, CV_32F, cv::Scalar(0));
  cv::Mat outline_px(80, 80, CV_32F);
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 80; ++x) outline_px.at<float>(y, x) = float(1 + std::min({x, y, 79 - x, 79 - y}));
  // The strip: rows 39-41, from the outline across to the middle.
  for (int y = 39; y <= 41; ++y)
    for (int x = 0; x < 40; ++x) {
      render.at<cv::Vec3f>(y, x) = cv::Vec3f(20, 15, 12);
      turned.at<float>(y, x) = 1.0f;
    }
  soften_turned_away(render, turned, outline_px, fade);
  // Deep inside (over 16 px from the outline): the surrounding skin.
  const cv::Vec3f deep = render.at<cv::Vec3f>(40, 30);
  EXPECT_NEAR(deep[0], 200.0f, 1.0f);
  EXPECT_NEAR(deep[2], 120.0f, 1.0f);
  // Within the band, near the outline: unchanged (the alpha fades it there).
  EXPECT_EQ(render.at<cv::Vec3f>(40, 3), cv::Vec3f(20, 15, 12));
  // Between, partly.
  const float between = render.at<cv::Vec3f>(40, 11)[0];
  EXPECT_GT(between, 30.0f);
  EXPECT_LT(between, 190.0f);
  // The skin facing the camera keeps its colour.
  EXPECT_EQ(render.at<cv::Vec3f>(20, 20), cv::Vec3f(200, 150, 120));
}

}  // namespace facecap
