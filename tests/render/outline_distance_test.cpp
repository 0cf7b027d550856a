#include "facecap/render/outline_distance.hpp"

#include <gtest/gtest.h>

namespace facecap {

namespace {

// Buffers 60 x 40 with the pixels `drawn` says drawn (triangle 0).
template <typename Drawn>
RasterBuffers buffers_with(Drawn drawn) {
  RasterBuffers b;
  b.resize(60, 40);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      if (drawn(x, y)) b.triangle[size_t(y) * b.width + x] = 0;
  return b;
}

}  // namespace

TEST(OutlineDistance, MeasuresFromTheOuterOutlineAndHolesCountAsInside) {
  // A rectangle [10, 49] x [5, 34] with a hole [25, 34] x [15, 24] in it.
  const RasterBuffers b = buffers_with([](int x, int y) {
    const bool rect = x >= 10 && x <= 49 && y >= 5 && y <= 34;
    const bool hole = x >= 25 && x <= 34 && y >= 15 && y <= 24;
    return rect && !hole;
  });
  const cv::Mat d = outline_distance(b);
  ASSERT_EQ(d.type(), CV_32F);
  ASSERT_EQ(d.size(), cv::Size(60, 40));
  EXPECT_EQ(d.at<float>(0, 0), 0.0f);             // outside
  EXPECT_EQ(d.at<float>(20, 5), 0.0f);            // outside, left of the rectangle
  EXPECT_NEAR(d.at<float>(20, 10), 1.0f, 0.05f);  // its first column
  EXPECT_NEAR(d.at<float>(20, 14), 5.0f, 0.3f);   // (a chamfer distance: within 5 %)
  // The hole is 10 px from the rectangle's edge at its own left edge, not 1
  // px from the hole: the eye and mouth openings are not the outline.
  EXPECT_NEAR(d.at<float>(20, 24), 15.0f, 0.8f);
  EXPECT_NEAR(d.at<float>(20, 29), 15.0f, 1.0f);  // in the hole: 15 px to the rectangle's bottom
  // Its last column and row, and what lies beyond them.
  EXPECT_NEAR(d.at<float>(20, 49), 1.0f, 0.05f);
  EXPECT_EQ(d.at<float>(20, 50), 0.0f);
  EXPECT_NEAR(d.at<float>(34, 40), 1.0f, 0.05f);
  EXPECT_EQ(d.at<float>(35, 40), 0.0f);
  EXPECT_NEAR(d.at<float>(33, 48), 2.0f, 0.1f);
}

TEST(OutlineDistance, NothingDrawnIsNothingInside) {
  const cv::Mat d = outline_distance(buffers_with([](int, int) { return false; }));
  ASSERT_EQ(d.size(), cv::Size(60, 40));
  EXPECT_EQ(cv::countNonZero(d), 0);
}

TEST(OutlineDistance, ARenderAtTheBuffersEdgeEndsThere) {
  const RasterBuffers b = buffers_with([](int, int) { return true; });
  const cv::Mat d = outline_distance(b);
  EXPECT_NEAR(d.at<float>(0, 0), 1.0f, 0.05f);
  EXPECT_NEAR(d.at<float>(20, 30), 20.0f, 1.0f);  // 20 px to the bottom
}

}  // namespace facecap
