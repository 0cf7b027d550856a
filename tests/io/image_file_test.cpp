#include "facecap/io/image_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <opencv2/imgproc.hpp>
#include <string>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A 64x48 BGR image with a different colour in each corner region, so that
// a flip or a turn shows.
cv::Mat corner_image() {
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(40, 80, 120));
  image(cv::Rect(0, 0, 16, 12)).setTo(cv::Scalar(255, 0, 0));
  image(cv::Rect(48, 0, 16, 12)).setTo(cv::Scalar(0, 255, 0));
  image(cv::Rect(0, 36, 16, 12)).setTo(cv::Scalar(0, 0, 255));
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x)[1] = cv::saturate_cast<uchar>(x * 3 + y);
  return image;
}

double max_difference(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  return cv::norm(a, b, cv::NORM_INF);
}

// The JPEG with an APP1 segment holding only an EXIF orientation tag.
std::vector<unsigned char> with_orientation(const std::vector<unsigned char>& jpeg, int orientation) {
  const unsigned char tiff[] = {'M',  'M',  0, 42, 0, 0, 0, 8,  // big-endian, IFD0 at 8
                                0,    1,                        // one entry
                                0x01, 0x12, 0, 3,  0, 0, 0, 1, 0, (unsigned char)orientation,
                                0,    0,    0, 0,  0, 0};  // no next IFD
  std::vector<unsigned char> payload = {'E', 'x', 'i', 'f', 0, 0};
  payload.insert(payload.end(), std::begin(tiff), std::end(tiff));
  const size_t length = payload.size() + 2;
  const unsigned char head[] = {0xff, 0xd8, 0xff, 0xe1, (unsigned char)(length >> 8), (unsigned char)length};
  std::vector<unsigned char> out(std::size(head) + payload.size() + jpeg.size() - 2);
  auto at = std::copy(std::begin(head), std::end(head), out.begin());
  at = std::copy(payload.begin(), payload.end(), at);
  std::copy(jpeg.begin() + 2, jpeg.end(), at);
  return out;
}

}  // namespace

TEST(ImageFile, PngKeepsEveryPixelOfGreyColourAndAlphaImages) {
  const cv::Mat bgr = corner_image();
  EXPECT_EQ(max_difference(decode_image(encode_png(bgr)), bgr), 0.0);
  cv::Mat grey, grey_as_bgr, bgra, bgra_as_bgr;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(grey, grey_as_bgr, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(max_difference(decode_image(encode_png(grey)), grey_as_bgr), 0.0);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  bgra.col(5).setTo(cv::Scalar(1, 2, 3, 0));  // a transparent column keeps its colour
  cv::cvtColor(bgra, bgra_as_bgr, cv::COLOR_BGRA2BGR);
  EXPECT_EQ(max_difference(decode_image(encode_png(bgra)), bgra_as_bgr), 0.0);
  // A view into a larger image (rows not contiguous).
  const cv::Mat wide = cv::repeat(bgr, 1, 2);
  EXPECT_EQ(max_difference(decode_image(encode_png(wide(cv::Rect(64, 0, 64, 48)))), bgr), 0.0);
  EXPECT_THROW(encode_png(cv::Mat(4, 4, CV_32FC3)), Error);
}

TEST(ImageFile, JpegAtQuality95IsCloseAndATurnedOneIsTurnedUpright) {
  const cv::Mat bgr = corner_image();
  const std::vector<unsigned char> jpeg = encode_jpeg(bgr, 95);
  const cv::Mat back = decode_image(jpeg);
  ASSERT_EQ(back.size(), bgr.size());
  cv::Mat error;
  cv::absdiff(back, bgr, error);
  EXPECT_LT(cv::mean(error)[0] + cv::mean(error)[1] + cv::mean(error)[2], 3 * 3.0);
  // EXIF orientations as cameras write them (and cv::imread applies them):
  // 6 means the picture must be turned 90 degrees clockwise, 8 counter-
  // clockwise, 3 half a turn, 2 mirrored.
  const std::vector<std::pair<int, int>> turns = {
      {6, cv::ROTATE_90_CLOCKWISE}, {8, cv::ROTATE_90_COUNTERCLOCKWISE}, {3, cv::ROTATE_180}};
  for (const auto& [orientation, rotation] : turns) {
    cv::Mat expected;
    cv::rotate(back, expected, rotation);
    EXPECT_EQ(max_difference(decode_image(with_orientation(jpeg, orientation)), expected), 0.0) << orientation;
  }
  cv::Mat mirrored;
  cv::flip(back, mirrored, 1);
  EXPECT_EQ(max_difference(decode_image(with_orientation(jpeg, 2)), mirrored), 0.0);
  EXPECT_EQ(max_difference(decode_image(with_orientation(jpeg, 1)), back), 0.0);
}

TEST(ImageFile, OtherFormatsAreReadAndBadBytesGiveNoImage) {
  const cv::Mat bgr = corner_image();
  // A binary PPM: a header, then RGB bytes.
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  std::string ppm = "P6\n64 48\n255\n";
  ppm.append(reinterpret_cast<const char*>(rgb.data), rgb.total() * 3);
  EXPECT_EQ(
      max_difference(decode_image(std::span(reinterpret_cast<const unsigned char*>(ppm.data()), ppm.size())), bgr),
      0.0);
  const std::string text = "this is not an image";
  EXPECT_TRUE(decode_image(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size())).empty());
  std::vector<unsigned char> cut = encode_png(bgr);
  cut.resize(40);
  EXPECT_TRUE(decode_image(cut).empty());
  const std::vector<unsigned char> not_quite_jpeg = {0xff, 0xd8, 0xff, 0xe0, 0, 2, 1, 2, 3};
  EXPECT_TRUE(decode_image(not_quite_jpeg).empty());
  EXPECT_TRUE(read_image("/nonexistent/image.png").empty());
}

TEST(ImageFile, WriteImageChoosesTheFormatByNameAndRefusesOthers) {
  TempDir dir;
  const cv::Mat bgr = corner_image();
  write_image(dir.path() / "a.png", bgr);
  EXPECT_EQ(max_difference(read_image(dir.path() / "a.png"), bgr), 0.0);
  write_image(dir.path() / "b.JPG", bgr);
  std::ifstream jpeg(dir.path() / "b.JPG", std::ios::binary);
  unsigned char magic[2] = {0, 0};
  jpeg.read(reinterpret_cast<char*>(magic), 2);
  EXPECT_EQ(magic[0], 0xff);
  EXPECT_EQ(magic[1], 0xd8);
  EXPECT_EQ(read_image(dir.path() / "b.JPG").size(), bgr.size());
  EXPECT_THROW(write_image(dir.path() / "c.gif", bgr), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "c.gif"));
}

// The footage's photos decode to exactly what cv::imread gave them: the sums
// of their channels, measured with OpenCV 4.6's imread before imgcodecs was
// replaced (it is no longer linked), as a fingerprint of every pixel.
TEST(ImageFile, ThePortraitsDecodeToWhatOpenCvGave) {
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(biden, "portrait_biden.jpg");
  FACECAP_REQUIRE_DATA(lfpw, "lfpw_image_0010.png");
  const std::vector<std::pair<fs::path, cv::Scalar>> expected = {{obama, cv::Scalar(77231825, 74156814, 98323336)},
                                                                 {biden, cv::Scalar(118681756, 134069180, 151247008)},
                                                                 {lfpw, cv::Scalar(63700880, 122266158, 184651068)}};
  for (const auto& [file, sums] : expected) {
    const cv::Scalar ours = cv::sum(read_image(file));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(ours[c], sums[c]) << file << " channel " << c;
  }
}

}  // namespace facecap
