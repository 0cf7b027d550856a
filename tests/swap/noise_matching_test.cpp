#include "facecap/swap/noise_matching.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace facecap {

namespace {

cv::Mat noise(double sigma, int seed) {
  cv::Mat m(128, 128, CV_32FC3);
  cv::RNG(seed).fill(m, cv::RNG::NORMAL, 0.0, sigma);
  return m;
}

double stddev(const cv::Mat& m, int channel) {
  cv::Scalar mean, sd;
  cv::meanStdDev(m, mean, sd);
  return sd[channel];
}

}  // namespace

TEST(NoiseMatching, SourceTakesTheTargetsSpread) {
  const cv::Mat source = noise(0.06, 1), target = noise(0.015, 2);
  const cv::Mat all(128, 128, CV_8U, cv::Scalar(255));
  const cv::Mat matched = match_histograms(source, all, target, all, -0.3f, 0.3f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(stddev(matched, c), 0.015, 0.0025) << c;  // 256 bins of 0.0023 over [-0.3, 0.3]
    EXPECT_NEAR(cv::mean(matched)[c], 0.0, 0.002);
  }
  // Monotone: the order of the source values is kept.
  const float a = source.at<cv::Vec3f>(3, 4)[0], b = source.at<cv::Vec3f>(50, 60)[0];
  const float ma = matched.at<cv::Vec3f>(3, 4)[0], mb = matched.at<cv::Vec3f>(50, 60)[0];
  if (std::abs(a - b) > 0.01f) {
    EXPECT_EQ(a < b, ma < mb);
  }
}

TEST(NoiseMatching, OnlyMaskedTexelsCount) {
  cv::Mat target = noise(0.01, 3);
  cv::Mat mask(128, 128, CV_8U, cv::Scalar(255));
  mask(cv::Rect(0, 0, 128, 64)).setTo(0);
  target(cv::Rect(0, 0, 128, 64)).setTo(cv::Scalar::all(0.25));  // outside the face: ignored
  const cv::Mat matched = match_histograms(noise(0.05, 4), mask, target, mask, -0.3f, 0.3f);
  EXPECT_NEAR(stddev(matched(cv::Rect(0, 64, 128, 64)), 1), 0.01, 0.003);
}

TEST(NoiseMatching, FineResidualOfASmoothImageIsZero) {
  const cv::Mat flat(64, 64, CV_32FC3, cv::Scalar(0.3, 0.4, 0.5));
  double worst = 0;
  const cv::Mat r = cv::abs(fine_residual(flat, 2.0));
  cv::minMaxLoc(r.reshape(1), nullptr, &worst);
  EXPECT_LT(worst, 1e-5);
}

}  // namespace facecap
