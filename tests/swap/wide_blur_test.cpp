#include "facecap/swap/wide_blur.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

// A texture-like test image: skin-toned noise with a few hard-edged dark
// patches (brows, lips) and a bright square, three channels.
cv::Mat test_texture(int size) {
  cv::Mat image(size, size, CV_32FC3);
  cv::RNG(11).fill(image, cv::RNG::UNIFORM, cv::Scalar(0.4, 0.5, 0.6), cv::Scalar(0.5, 0.6, 0.8));
  cv::rectangle(image, cv::Rect(size / 4, size / 4, size / 5, size / 30), cv::Scalar(0.1, 0.1, 0.15), -1);
  cv::ellipse(image, cv::Point(size / 2, 3 * size / 4), cv::Size(size / 8, size / 20), 0, 0, 360,
              cv::Scalar(0.3, 0.3, 0.7), -1);
  cv::rectangle(image, cv::Rect(3 * size / 4, size / 8, size / 8, size / 8), cv::Scalar::all(1.0), -1);
  return image;
}

double largest_difference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

}  // namespace

TEST(WideBlur, ANarrowOneIsOpenCvsGaussian) {
  const cv::Mat image = test_texture(256);
  for (const double sigma : {1.0, 2.0, 7.9}) {
    cv::Mat exact;
    cv::GaussianBlur(image, exact, cv::Size(0, 0), sigma);
    EXPECT_EQ(largest_difference(wide_blur(image, sigma), exact), 0.0) << sigma;
  }
}

// The wide low-passes the swap takes of its 1024 textures (the mirror
// completion's 24 texels, the photo detail's 16): within a few thousandths
// of the exact blur, on an image whose values span 0.1-1. With zeros
// outside (the expression ratio's, which divides one such blur by another)
// that holds away from the edge; within two sigma of it the coarse grid's
// zeros come a fraction of a coarse texel early (measured 0.03).
TEST(WideBlur, AWideOneIsCloseToTheExactGaussian) {
  const cv::Mat image = test_texture(1024);
  for (const double sigma : {16.0, 24.0}) {
    cv::Mat exact;
    cv::GaussianBlur(image, exact, cv::Size(0, 0), sigma);
    EXPECT_LT(largest_difference(wide_blur(image, sigma), exact), 0.005) << sigma;
    cv::GaussianBlur(image, exact, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
    const int edge = static_cast<int>(2 * sigma);
    const cv::Rect inside(edge, edge, image.cols - 2 * edge, image.rows - 2 * edge);
    EXPECT_LT(largest_difference(wide_blur(image, sigma, cv::BORDER_CONSTANT)(inside), exact(inside)), 0.005) << sigma;
    EXPECT_LT(largest_difference(wide_blur(image, sigma, cv::BORDER_CONSTANT), exact), 0.05) << sigma;
  }
  // One channel as well (a weight).
  cv::Mat grey, exact;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(grey, exact, cv::Size(0, 0), 24.0);
  EXPECT_LT(largest_difference(wide_blur(grey, 24.0), exact), 0.005);
}

}  // namespace facecap
