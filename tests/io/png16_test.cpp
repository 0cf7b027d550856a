#include "facecap/io/png16.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"

namespace facecap {

namespace {

// An odd-sized 16-bit field of `channels` channels: each a smooth ramp of
// its own with noise in its low bits, the extremes in two corners (a detail
// map's or a UV pass's kind of content, and the values the Sub filter wraps
// around on).
cv::Mat test_field(int channels) {
  cv::Mat image(37, 53, CV_16UC(channels));
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> noise(-300, 300);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      for (int c = 0; c < channels; ++c)
        image.ptr<uint16_t>(y)[x * channels + c] =
            cv::saturate_cast<uint16_t>(20000 + (700 - 200 * c) * x - (300 + 100 * c) * y + noise(rng));
  image.ptr<uint16_t>(0)[0] = 0;
  image.ptr<uint16_t>(0)[channels] = 65535;
  image.ptr<uint16_t>(36)[52 * channels] = 65535;
  // Empty rows and rows empty at either end, as a UV pass's are outside the
  // face (the encoder filters only a row's span with values).
  for (int y = 10; y < 13; ++y) image.row(y).setTo(cv::Scalar::all(0));
  for (int y = 20; y < 31; ++y) {
    image.row(y).colRange(0, 7).setTo(cv::Scalar::all(0));
    image.row(y).colRange(45 + y % 3, 53).setTo(cv::Scalar::all(0));
  }
  // Alpha as a mask (a UV pass's coverage): opaque, or clear with nothing
  // under it, which read_png16's premultiplied read leaves as written.
  if (channels == 4)
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x) {
        uint16_t* p = image.ptr<uint16_t>(y) + 4 * x;
        p[3] = (x + y) % 5 == 0 ? 0 : 65535;
        if (p[3] == 0) p[0] = p[1] = p[2] = 0;
      }
  return image;
}

}  // namespace

// Every sample of every channel comes back as written, through the file, in
// OpenCV's channel order.
TEST(Png16, GreyColourAndAlphaFieldsRoundTripExactly) {
  for (int channels : {1, 3, 4}) {
    const cv::Mat field = test_field(channels);
    TempDir dir;
    const auto path = dir.path() / "field.png";
    write_image(path, field);  // encode_png hands 16-bit images on to encode_png16
    const cv::Mat back = read_png16(path);
    ASSERT_EQ(back.type(), field.type()) << channels;
    ASSERT_EQ(back.size(), field.size());
    EXPECT_EQ(cv::norm(back, field, cv::NORM_INF), 0.0) << channels << " channels";
  }
}

// An independent decoder (libavcodec's PNG, behind read_image) reads the
// files as conforming 16-bit PNGs: its 8-bit BGR view is the high byte, in
// the same channel order.
TEST(Png16, AnotherDecoderReadsTheSameField) {
  for (int channels : {1, 3}) {
    const cv::Mat field = test_field(channels);
    const cv::Mat bgr = decode_image(encode_png16(field));
    ASSERT_EQ(bgr.size(), field.size());
    cv::Mat seen, expected;
    if (channels == 1)
      cv::cvtColor(bgr, seen, cv::COLOR_BGR2GRAY);
    else
      seen = bgr;
    field.convertTo(expected, CV_8U, 1.0 / 257);
    EXPECT_LE(cv::norm(seen, expected, cv::NORM_INF), 1.0) << channels << " channels";
  }
}

TEST(Png16, RefusesAnotherKindOfImage) {
  EXPECT_THROW(encode_png16(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(encode_png16(cv::Mat(4, 4, CV_16UC2, cv::Scalar::all(0))), Error);
  EXPECT_THROW(encode_png16(cv::Mat()), Error);
}

// A file that is not a PNG, or is cut short, reads as nothing.
TEST(Png16, ATruncatedFileReadsAsNothing) {
  const std::vector<unsigned char> png = encode_png16(test_field(1));
  TempDir dir;
  const auto path = dir.path() / "cut.png";
  write_binary_file(path, png.data(), png.size() / 2);
  EXPECT_TRUE(read_png16(path).empty());
  EXPECT_TRUE(read_png16(dir.path() / "missing.png").empty());
}

}  // namespace facecap
