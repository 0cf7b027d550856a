#include "facecap/io/input.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

std::string open_error(const std::string& spec) {
  try {
    open_input(spec);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void write_prefix(const fs::path& from, const fs::path& to, double share) {
  std::ifstream in(from, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(to, std::ios::binary) << bytes.substr(0, size_t(bytes.size() * share));
}

}  // namespace

TEST(Input, OpensAVideoWithItsFacts) {
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  auto source = open_input(video.string());
  const InputInfo& info = source->info();
  EXPECT_EQ(info.kind, InputKind::kVideo);
  EXPECT_EQ(info.width, 1280);
  EXPECT_EQ(info.height, 720);
  EXPECT_NEAR(info.fps, 29.97, 0.01);
  EXPECT_EQ(info.frames, 144);
  EXPECT_TRUE(info.audio);
  Frame frame;
  int n = 0;
  while (source->read(frame)) {
    ASSERT_EQ(frame.index, n);
    ASSERT_EQ(frame.image.cols, 1280);
    ++n;
  }
  EXPECT_EQ(n, 144);
}

TEST(Input, WebcamClipHasNoAudio) {
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  EXPECT_FALSE(open_input(video.string())->info().audio);
}

TEST(Input, StillImageAndImageFolder) {
  TempDir dir;
  const cv::Mat img(60, 80, CV_8UC3, cv::Scalar(10, 20, 30));
  for (const char* name : {"b.png", "a.png", "c.jpg"}) cv::imwrite((dir.path() / name).string(), img);
  std::ofstream(dir.path() / "notes.txt") << "ignored";
  auto still = open_input((dir.path() / "a.png").string());
  EXPECT_EQ(still->info().kind, InputKind::kImage);
  Frame f;
  EXPECT_TRUE(still->read(f));
  EXPECT_FALSE(still->read(f));
  auto folder = open_input(dir.path().string());
  EXPECT_EQ(folder->info().kind, InputKind::kImageFolder);
  EXPECT_EQ(folder->info().frames, 3);
  EXPECT_EQ(folder->info().width, 80);
  int n = 0;
  while (folder->read(f)) ++n;
  EXPECT_EQ(n, 3);
}

TEST(Input, BadInputsGetOneClearMessage) {
  TempDir dir;
  EXPECT_NE(open_error((dir.path() / "missing.mp4").string()).find("input not found"), std::string::npos);
  EXPECT_NE(open_error(dir.path().string()).find("holds no images"), std::string::npos);
  std::ofstream(dir.path() / "empty.mp4").close();
  EXPECT_NE(open_error((dir.path() / "empty.mp4").string()).find("0 bytes"), std::string::npos);
  std::ofstream(dir.path() / "text.mp4") << "this is not a video\n";
  EXPECT_NE(open_error((dir.path() / "text.mp4").string()).find("not a video file or corrupt"), std::string::npos);
  std::ofstream(dir.path() / "text.png") << "this is not an image\n";
  EXPECT_NE(open_error((dir.path() / "text.png").string()).find("cannot decode image"), std::string::npos);
  EXPECT_NE(open_error("cam:x").find("cam:N"), std::string::npos);
  EXPECT_NE(open_error("").find("no input"), std::string::npos);
}

TEST(Input, TruncatedVideosAreRejectedWhereverTheIndexSits) {
  TempDir dir;
  // Index (moov) at the end: the cut file has none.
  FACECAP_REQUIRE_DATA(address, "address_720p_a.mp4");
  write_prefix(address, dir.path() / "cut_a.mp4", 0.5);
  const std::string a = open_error((dir.path() / "cut_a.mp4").string());
  EXPECT_NE(a.find("cut_a.mp4"), std::string::npos) << a;
  // Index at the start: it points past the end of the cut file.
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  write_prefix(webcam, dir.path() / "cut_b.mp4", 0.4);
  const std::string b = open_error((dir.path() / "cut_b.mp4").string());
  EXPECT_NE(b.find("truncated"), std::string::npos) << b;
}

}  // namespace facecap
