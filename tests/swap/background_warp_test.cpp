#include "facecap/swap/background_warp.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

cv::Mat textured() {
  cv::Mat img(200, 240, CV_8UC3);
  cv::RNG(5).fill(img, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 2);
  return img;
}

std::vector<cv::Point2f> ring(cv::Point2f c, float r, int n) {
  std::vector<cv::Point2f> p;
  for (int i = 0; i < n; ++i) p.emplace_back(c.x + r * std::cos(6.2832f * i / n), c.y + r * std::sin(6.2832f * i / n));
  p.push_back(c);
  return p;
}

}  // namespace

TEST(BackgroundWarp, UnmovedAnchorsLeaveTheFrame) {
  const cv::Mat frame = textured();
  const auto anchors = ring({120, 100}, 40, 12);
  const cv::Rect window(40, 20, 160, 160);
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, anchors, anchors, window, out);
  EXPECT_GT(warp.triangle_count(), 12);
  cv::Mat d;
  cv::absdiff(out, frame(window), d);
  double worst = 0;
  cv::minMaxLoc(d.reshape(1), nullptr, &worst);
  EXPECT_LE(worst, 1.0);
}

TEST(BackgroundWarp, AnchorsCarryTheirSurroundingsAndTheBorderStays) {
  const cv::Mat frame = textured();
  const auto from = ring({120, 100}, 40, 12);
  std::vector<cv::Point2f> to = from;
  for (auto& p : to) p += cv::Point2f(6, 0);  // the face moved 6 px right
  const cv::Rect window(40, 20, 160, 160);
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, from, to, window, out);
  // Inside the ring the content moved by 6 px: out(x + 6) == frame(x).
  for (int y = 90; y <= 110; y += 5) {
    for (int x = 110; x <= 130; x += 5) {
      const cv::Vec3b a = out.at<cv::Vec3b>(y - window.y, x + 6 - window.x), b = frame.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 2) << x << "," << y;
    }
  }
  // The window's border does not move.
  EXPECT_EQ(out.at<cv::Vec3b>(0, 0), frame.at<cv::Vec3b>(window.y, window.x));
  EXPECT_EQ(out.at<cv::Vec3b>(159, 159), frame.at<cv::Vec3b>(window.y + 159, window.x + 159));
}

// Beyond the fixed ring the background is untouched: the warp fades out
// around the face instead of bending everything up to the window's edge.
TEST(BackgroundWarp, TheBackgroundBeyondTheRingStaysPut) {
  const cv::Mat frame = textured();
  const auto from = ring({120, 100}, 30, 12);
  std::vector<cv::Point2f> to = from;
  for (auto& p : to) p += cv::Point2f(6, 0);
  const cv::Rect window(20, 10, 200, 180);
  const auto fixed = fixed_ring(from, to, window);
  ASSERT_EQ(static_cast<int>(fixed.size()), kRingPoints);
  for (const cv::Point2f& p : fixed) {
    EXPECT_TRUE(window.contains(cv::Point(int(p.x), int(p.y))));
    EXPECT_GT(cv::norm(p - cv::Point2f(120, 100)), 36.0);  // outside both anchor sets
  }
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, from, to, window, out);
  // Points between the ring (radius about 47) and the window's border.
  for (const cv::Point p :
       {cv::Point(30, 20), cv::Point(60, 40), cv::Point(200, 170), cv::Point(30, 150), cv::Point(190, 30)}) {
    EXPECT_EQ(out.at<cv::Vec3b>(p.y - window.y, p.x - window.x), frame.at<cv::Vec3b>(p)) << p;
  }
}

}  // namespace facecap
