#include "facecap/detect/upright_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

// A grey image of smooth, distinct content (bilinear sampling is near exact).
cv::Mat test_frame(int width, int height) {
  cv::Mat image(height, width, CV_8U);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at<uchar>(y, x) =
          cv::saturate_cast<uchar>(128 + 60 * std::sin(0.05 * x) + 50 * std::cos(0.07 * y + 0.01 * x));
  return image;
}

float sample(const cv::Mat& image, const Vec2f& p) {
  cv::Mat patch;
  cv::getRectSubPix(image, cv::Size(1, 1), cv::Point2f(p.x(), p.y()), patch, CV_32F);
  return patch.at<float>(0, 0);
}

}  // namespace

TEST(UprightView, ALineAtTheTurnLiesAlongTheViewsXAxis) {
  for (const float degrees : {45.0f, -45.0f, 90.0f, -90.0f, 135.0f, 180.0f}) {
    const UprightView view(cv::Size(400, 300), degrees);
    Landmarks lm = zero_landmarks();
    const float a = degrees * float(M_PI) / 180.0f;
    lm[36] = {200, 150};
    lm[45] = lm[36] + 50.0f * Vec2f(std::cos(a), std::sin(a));
    EXPECT_NEAR(roll_degrees(lm), degrees == 180.0f ? 180.0f : degrees, 1e-3f);
    const Landmarks in_view = view.to_view(lm);
    EXPECT_NEAR(roll_degrees(in_view), 0.0f, 1e-3f) << degrees;
    // And back.
    const Landmarks back = view.to_frame(in_view);
    for (int i : {36, 45}) EXPECT_LT((back[i] - lm[i]).norm(), 1e-3f) << degrees;
  }
}

TEST(UprightView, TheImageShowsTheFrameWhereTheMappingSays) {
  const cv::Mat frame = test_frame(160, 120);
  for (const float degrees : {0.0f, 45.0f, -45.0f, 90.0f, -90.0f, 135.0f, 180.0f}) {
    for (const float scale : {1.0f, 0.5f}) {
      const UprightView view(frame, degrees, scale);
      ASSERT_EQ(view.image().size(), view.size());
      // The whole frame fits: its corners map inside the view.
      for (const Vec2f& corner : {Vec2f(0, 0), Vec2f(159, 0), Vec2f(0, 119), Vec2f(159, 119)}) {
        const Vec2f q = view.to_view(corner);
        EXPECT_GT(q.x(), -1.0f) << degrees;
        EXPECT_GT(q.y(), -1.0f) << degrees;
        EXPECT_LT(q.x(), float(view.size().width)) << degrees;
        EXPECT_LT(q.y(), float(view.size().height)) << degrees;
      }
      double error = 0;
      int n = 0;
      for (int y = 20; y < 100; y += 7)
        for (int x = 20; x < 140; x += 7) {
          const Vec2f p{float(x), float(y)};
          error += std::abs(sample(view.image(), view.to_view(p)) - frame.at<uchar>(y, x));
          ++n;
        }
      // Within bilinear resampling of smooth content (twice at half size).
      EXPECT_LT(error / n, scale == 1.0f ? 1.0 : 3.0) << degrees << " at " << scale;
    }
  }
  // Upright at full size: the frame itself, not a copy.
  EXPECT_EQ(UprightView(frame, 0).image().data, frame.data);
}

TEST(UprightView, BoxesTurnToTheBoxAroundTheirCorners) {
  const UprightView view(cv::Size(400, 300), 90);
  const Box b{100, 50, 40, 20};
  const Box v = view.to_view(b);
  EXPECT_NEAR(v.width, 20, 1e-3);
  EXPECT_NEAR(v.height, 40, 1e-3);
  const Box back = view.to_frame(v);
  EXPECT_NEAR(back.x, b.x, 1e-3);
  EXPECT_NEAR(back.y, b.y, 1e-3);
  EXPECT_NEAR(back.width, b.width, 1e-3);
  EXPECT_NEAR(back.height, b.height, 1e-3);
}

}  // namespace facecap
