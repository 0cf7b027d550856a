#include "facecap/io/marked_image.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/synthetic_mark.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

cv::Mat test_image() {
  cv::Mat m(48, 64, CV_8UC3);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(4 * x), uchar(5 * y), uchar(90));
  return m;
}

SyntheticMark test_mark() {
  SyntheticMark mark;
  mark.kind = "face-swap";
  mark.description = "A \"test\" of <marks> & names: Zoë.jpg.";  // XML's specials and UTF-8
  return mark;
}

}  // namespace

// Both formats decode as before, and carry the marks in the file: the tags
// read back, IPTC's DigitalSourceType in the XMP, and the comment in full.
TEST(MarkedImage, PngAndJpegCarryTheSyntheticMarks) {
  TempDir dir;
  const cv::Mat image = test_image();
  const auto tags = synthetic_metadata(test_mark());
  for (const char* name : {"out.png", "out.JPG", "out.jpeg"}) {
    const fs::path path = dir.path() / name;
    write_marked_image(path, image, tags);
    const cv::Mat back = facecap::read_image(path.string());
    ASSERT_EQ(back.size(), image.size()) << name;
    const double diff = cv::norm(back, image, cv::NORM_INF);
    if (path.extension() == ".png") {
      EXPECT_EQ(diff, 0.0) << name;
    } else {
      EXPECT_LT(diff, 24.0) << name;  // JPEG at quality 95
    }
    const auto read = read_image_tags(path);
    EXPECT_EQ(read.at("synthetic"), "true") << name;
    EXPECT_EQ(read.at("facecap_edit"), "face-swap") << name;
    EXPECT_EQ(read.at("xmp_digital_source_type"), "http://cv.iptc.org/newscodes/digitalsourcetype/compositeSynthetic")
        << name;
    EXPECT_EQ(read.at(path.extension() == ".png" ? "Comment" : "comment"), tags.at("comment")) << name;
    EXPECT_FALSE(carries_synthetic_marks(path)) << name;  // no sidecar yet
    write_synthetic_sidecar(path, test_mark());
    EXPECT_TRUE(carries_synthetic_marks(path)) << name;
  }
}

TEST(MarkedImage, AnImageWithoutMarksOrAnotherFileHasNoTags) {
  TempDir dir;
  const fs::path plain = dir.path() / "plain.png";
  facecap::write_image(plain.string(), test_image());
  EXPECT_TRUE(read_image_tags(plain).empty());
  std::ofstream(dir.path() / "text.jpg") << "not an image";
  EXPECT_TRUE(read_image_tags(dir.path() / "text.jpg").empty());
  EXPECT_TRUE(read_image_tags(dir.path() / "missing.png").empty());
  std::ofstream(plain.string() + ".json") << "{}";
  EXPECT_FALSE(carries_synthetic_marks(plain));  // a sidecar alone is not both marks
}

TEST(MarkedImage, AnotherNameOrNoImageIsAnErrorAndWritesNothing) {
  TempDir dir;
  const auto tags = synthetic_metadata(test_mark());
  EXPECT_THROW(write_marked_image(dir.path() / "out.gif", test_image(), tags), Error);
  EXPECT_THROW(write_marked_image(dir.path() / "out.png", cv::Mat(), tags), Error);
  EXPECT_TRUE(fs::is_empty(dir.path()));
  EXPECT_TRUE(is_still_image_path("a/B.JpEg"));
  EXPECT_FALSE(is_still_image_path("a/b.mp4"));
}

}  // namespace facecap
