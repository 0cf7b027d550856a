#include "facecap/compose/surface_exposure.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

// A strip of two squares (vertices 0-2 along the bottom, 3-5 along the top),
// 1 cm on a side, 50 cm in front of a 500 px camera: 10 px squares.
struct Strip {
  PinholeCamera camera = PinholeCamera::centered(500, 200, 200);
  Positions points = Positions(3, 6);
  std::vector<Triangle> triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  Strip() {
    for (int v = 0; v < 6; ++v) points.col(v) = Vec3f(float(v % 3), float(v / 3), 50.0f);
  }
};

}  // namespace

TEST(SurfaceExposure, ASurfaceThatOnlyMovesIsSeenWhole) {
  const Strip s;
  Positions moved = s.points;
  moved.row(0).array() += 0.3f;  // a shift, no stretch
  for (const float e : vertex_exposure(s.points, moved, s.triangles, s.camera)) EXPECT_NEAR(e, 1.0f, 1e-4f);
}

// The right square's top-right corner folded onto its bottom-right one in
// the frame, and unfolded now: the triangle between them was seen edge-on
// (not at all), the other of that square whole. A vertex's exposure is the
// seen share of its triangles' area now.
TEST(SurfaceExposure, WhatWasFoldedAwayWasNotSeen) {
  const Strip s;
  Positions folded = s.points;
  folded(1, 5) = folded(1, 2);
  folded(0, 5) = folded(0, 2) + 1e-4f;
  const std::vector<float> e = vertex_exposure(folded, s.points, s.triangles, s.camera);
  EXPECT_NEAR(e[2], 0.0f, 1e-3f);      // only {1, 2, 5}
  EXPECT_NEAR(e[5], 0.5f, 1e-3f);      // {1, 2, 5} unseen, {1, 5, 4} seen
  EXPECT_NEAR(e[1], 2.0f / 3, 1e-3f);  // and {0, 1, 4} seen
  for (const int v : {0, 3, 4}) EXPECT_NEAR(e[v], 1.0f, 1e-3f);
}

TEST(SurfaceExposure, ATriangleTurnedOverCountsAsUnseen) {
  const Strip s;
  Positions turned = s.points;
  turned(0, 2) = -1.0f;  // the right square's bottom-right corner past the middle: {1, 2, 5} turns over
  const std::vector<float> e = vertex_exposure(turned, s.points, s.triangles, s.camera);
  EXPECT_EQ(e[2], 0.0f);  // its only triangle was seen from behind
}

TEST(SurfaceExposure, TrustFallsSmoothlyFromSeenToUnseen) {
  EXPECT_EQ(exposure_trust(1.0f), 1.0f);
  EXPECT_EQ(exposure_trust(kSeenExposure), 1.0f);
  EXPECT_EQ(exposure_trust(kUnseenExposure), 0.0f);
  EXPECT_EQ(exposure_trust(0.0f), 0.0f);
  const float middle = 0.5f * (kSeenExposure + kUnseenExposure);
  EXPECT_NEAR(exposure_trust(middle), 0.5f, 1e-5f);
  EXPECT_LT(exposure_trust(middle - 0.01f), exposure_trust(middle));
}

// A pale spot where the trust is 0 (a stretched highlight) takes the colour
// of the trusted skin around it, not of what lies beyond the surface (an
// eye, the background: magenta below); the trusted pixels keep theirs, and
// where the trust is partial the two mix.
TEST(SurfaceExposure, AnUntrustedSpotTakesTheColourAroundIt) {
  cv::Mat colour(80, 80, CV_8UC3, cv::Scalar(60, 90, 150));
  cv::circle(colour, {40, 40}, 6, cv::Scalar(235, 235, 235), cv::FILLED);
  cv::Mat trust(80, 80, CV_32F, cv::Scalar(1.0f));
  cv::circle(trust, {40, 40}, 10, cv::Scalar(0.0f), cv::FILLED);
  trust.at<float>(10, 10) = 0.5f;
  colour.at<cv::Vec3b>(10, 10) = cv::Vec3b(0, 0, 0);
  cv::Mat surface(80, 80, CV_8U, cv::Scalar(255));
  cv::rectangle(surface, cv::Rect(0, 60, 80, 20), cv::Scalar(0), cv::FILLED);  // not skin: counts for nothing
  colour(cv::Rect(0, 60, 80, 20)).setTo(cv::Scalar(255, 0, 255));
  const cv::Mat before = colour.clone();
  fill_untrusted(colour, trust, surface, 5.0);
  EXPECT_EQ(colour.at<cv::Vec3b>(40, 40), cv::Vec3b(60, 90, 150));
  EXPECT_EQ(colour.at<cv::Vec3b>(30, 40), cv::Vec3b(60, 90, 150));
  EXPECT_EQ(colour.at<cv::Vec3b>(49, 40), cv::Vec3b(60, 90, 150));  // 11 px from the magenta
  EXPECT_EQ(colour.at<cv::Vec3b>(10, 10), cv::Vec3b(30, 45, 75));   // half its own, half the skin's
  cv::Mat changed;
  cv::absdiff(colour, before, changed);
  cv::cvtColor(changed, changed, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::countNonZero(changed & (trust >= 1.0f)), 0);
}

}  // namespace facecap
