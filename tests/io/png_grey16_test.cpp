#include "facecap/io/png_grey16.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"

namespace facecap {

namespace {

// An odd-sized 16-bit field: a smooth ramp with noise in its low bits, the
// extremes in two corners (a detail map's kind of content, and the values
// the Sub filter wraps around on).
cv::Mat test_field() {
  cv::Mat image(37, 53, CV_16UC1);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> noise(-300, 300);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      image.at<uint16_t>(y, x) = cv::saturate_cast<uint16_t>(20000 + 700 * x - 300 * y + noise(rng));
  image.at<uint16_t>(0, 0) = 0;
  image.at<uint16_t>(0, 1) = 65535;
  image.at<uint16_t>(36, 52) = 65535;
  return image;
}

}  // namespace

// Every sample comes back as written, through the file.
TEST(PngGrey16, ASixteenBitFieldRoundTripsExactly) {
  const cv::Mat field = test_field();
  TempDir dir;
  const auto path = dir.path() / "field.png";
  write_image(path, field);  // encode_png hands 16-bit grey on to encode_png_grey16
  const cv::Mat back = read_png_grey16(path);
  ASSERT_EQ(back.type(), CV_16UC1);
  ASSERT_EQ(back.size(), field.size());
  EXPECT_EQ(cv::norm(back, field, cv::NORM_INF), 0.0);
}

// An independent decoder (libavcodec's PNG, behind read_image) reads the
// file as a conforming 16-bit grey PNG: its 8-bit view is the high byte.
TEST(PngGrey16, AnotherDecoderReadsTheSameField) {
  const cv::Mat field = test_field();
  const std::vector<unsigned char> png = encode_png_grey16(field);
  const cv::Mat bgr = decode_image(png);
  ASSERT_EQ(bgr.size(), field.size());
  cv::Mat grey, expected;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  field.convertTo(expected, CV_8U, 1.0 / 257);
  EXPECT_LE(cv::norm(grey, expected, cv::NORM_INF), 1.0);
}

TEST(PngGrey16, RefusesAnotherKindOfImage) {
  EXPECT_THROW(encode_png_grey16(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(encode_png_grey16(cv::Mat(4, 4, CV_16UC3, cv::Scalar::all(0))), Error);
  EXPECT_THROW(encode_png_grey16(cv::Mat()), Error);
}

// A file that is not a PNG, or is cut short, reads as nothing.
TEST(PngGrey16, ATruncatedFileReadsAsNothing) {
  const std::vector<unsigned char> png = encode_png_grey16(test_field());
  TempDir dir;
  const auto path = dir.path() / "cut.png";
  write_binary_file(path, png.data(), png.size() / 2);
  EXPECT_TRUE(read_png_grey16(path).empty());
  EXPECT_TRUE(read_png_grey16(dir.path() / "missing.png").empty());
}

}  // namespace facecap
