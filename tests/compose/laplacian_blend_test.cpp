#include "facecap/compose/laplacian_blend.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

cv::Mat textured(int w, int h, int seed) {
  cv::Mat img(h, w, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 20, 230);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 1.5);
  return img;
}

double max_abs_diff(const cv::Mat& a, const cv::Mat& b) {
  double m = 0;
  cv::Mat d;
  cv::absdiff(a, b, d);
  cv::minMaxLoc(d.reshape(1), nullptr, &m);
  return m;
}

}  // namespace

TEST(LaplacianBlend, ALayerEqualToTheBaseChangesNothing) {
  const cv::Mat base = textured(160, 120, 1);
  cv::Mat mask(base.size(), CV_8U, cv::Scalar(0));
  cv::circle(mask, {80, 60}, 40, cv::Scalar(255), -1);
  EXPECT_EQ(max_abs_diff(laplacian_blend(base, base, feather_mask(mask, 2, 3)), base), 0.0);
}

TEST(LaplacianBlend, FullAndEmptyMasksPickOneImage) {
  const cv::Mat base = textured(128, 96, 2), layer = textured(128, 96, 3);
  EXPECT_LE(max_abs_diff(laplacian_blend(base, layer, cv::Mat(base.size(), CV_8U, cv::Scalar(255))), layer), 1.0);
  EXPECT_EQ(max_abs_diff(laplacian_blend(base, layer, cv::Mat(base.size(), CV_8U, cv::Scalar(0))), base), 0.0);
}

TEST(LaplacianBlend, InsideTheMaskTheLayerOutsideTheBaseAndNoHardSeam) {
  // The mask is large against the coarsest band (16 px at 5 levels), as a face is.
  const cv::Mat base(240, 320, CV_8UC3, cv::Scalar(60, 60, 60));
  const cv::Mat layer(240, 320, CV_8UC3, cv::Scalar(200, 200, 200));
  cv::Mat mask(base.size(), CV_8U, cv::Scalar(0));
  cv::rectangle(mask, cv::Rect(40, 30, 240, 180), cv::Scalar(255), -1);
  const cv::Mat out = laplacian_blend(base, layer, feather_mask(mask, 2, 3));
  EXPECT_NEAR(out.at<cv::Vec3b>(120, 160)[0], 200, 1);  // centre of the mask
  EXPECT_NEAR(out.at<cv::Vec3b>(5, 5)[0], 60, 3);       // far outside
  // Across the mask's left edge the profile climbs steadily over many
  // pixels: no pixel-to-pixel jump of more than a fifth of the 140 step.
  int largest_step = 0;
  for (int x = 20; x < 60; ++x) {
    const int step = out.at<cv::Vec3b>(120, x + 1)[0] - out.at<cv::Vec3b>(120, x)[0];
    EXPECT_GE(step, -1) << "x " << x;
    largest_step = std::max(largest_step, step);
  }
  EXPECT_LT(largest_step, 28);
}

TEST(FaceLayer, CompositingAnUntouchedLayerLeavesTheFrameExactly) {
  cv::Mat frame = textured(200, 150, 4);
  const cv::Mat before = frame.clone();
  FaceLayer layer = make_layer(frame, cv::Rect(150, 100, 80, 80), 16);  // clipped at the frame's corner
  EXPECT_EQ(layer.box, cv::Rect(134, 84, 66, 66));
  cv::rectangle(layer.mask, cv::Rect(10, 10, 30, 30), cv::Scalar(255), -1);
  composite_layer(frame, layer);
  EXPECT_EQ(max_abs_diff(frame, before), 0.0);
}

TEST(FaceLayer, CompositingPutsTheLayerInItsWindowOnly) {
  cv::Mat frame(300, 400, CV_8UC3, cv::Scalar(50, 50, 50));
  FaceLayer layer = make_layer(frame, cv::Rect(100, 60, 200, 180), 32);
  cv::rectangle(layer.colour, cv::Rect(32, 32, 200, 180), cv::Scalar(250, 250, 250), -1);
  cv::rectangle(layer.mask, cv::Rect(32, 32, 200, 180), cv::Scalar(255), -1);
  composite_layer(frame, layer);
  EXPECT_GE(frame.at<cv::Vec3b>(150, 200)[1], 249);
  EXPECT_EQ(frame.at<cv::Vec3b>(5, 5)[1], 50);
  EXPECT_EQ(frame.at<cv::Vec3b>(295, 395)[1], 50);
}

TEST(LaplacianBlend, ImagesOfAnotherTypeOrSizeAreAnError) {
  const cv::Mat base(32, 32, CV_8UC3, cv::Scalar::all(9)), mask(32, 32, CV_8U, cv::Scalar(255));
  EXPECT_THROW(laplacian_blend(base, cv::Mat(32, 32, CV_32FC3, cv::Scalar::all(9)), mask), Error);
  EXPECT_THROW(laplacian_blend(base, cv::Mat(32, 31, CV_8UC3, cv::Scalar::all(9)), mask), Error);
  EXPECT_THROW(laplacian_blend(base, base, cv::Mat(32, 32, CV_32F, cv::Scalar(1))), Error);
}

}  // namespace facecap
