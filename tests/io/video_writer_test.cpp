#include "facecap/io/video_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

cv::Mat gradient_frame(int i, int w, int h) {
  cv::Mat m(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(x + i), uchar(y), uchar(128));
  return m;
}

// Options for 64 x 64 frames, the rest as they come.
VideoWriterOptions small_frames() {
  VideoWriterOptions o;
  o.width = 64;
  o.height = 64;
  return o;
}

constexpr const char* kPreviousOutput = "previous good output";

// A good file where the output goes, which a write that fails must leave.
fs::path previous_output(const TempDir& dir) {
  const fs::path out = dir.path() / "keep.mp4";
  std::ofstream(out) << kPreviousOutput;
  return out;
}

// Whether `out` still holds it, alone in its folder (no partial left).
bool only_the_previous_output(const fs::path& out) {
  std::ifstream in(out);
  std::string content;
  std::getline(in, content);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out.parent_path())) ++files;
  return content == kPreviousOutput && files == 1;
}

}  // namespace

TEST(VideoWriter, WritesH264WithTheInputsAudioAndMetadata) {
  FACECAP_REQUIRE_DATA(source, "address_720p_a.mp4");
  TempDir dir;
  const fs::path out = dir.path() / "out.mp4";
  SyntheticMark mark{"expression-transform", "test", {source.string()}, {}};
  VideoWriterOptions o;
  o.width = 160;
  o.height = 90;
  o.fps = 29.97;
  o.audio_source = source;
  o.metadata = synthetic_metadata(mark);
  {
    VideoWriter w(out, o);
    for (int i = 0; i < 30; ++i) w.write(gradient_frame(i, 160, 90));
    w.finish();
  }
  const InputInfo info = probe_video_file(out);
  EXPECT_EQ(info.width, 160);
  EXPECT_EQ(info.frames, 30);
  EXPECT_TRUE(info.audio);
  // The container carries the synthetic tag.
  std::ifstream in(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("SYNTHETIC MEDIA"), std::string::npos);
  EXPECT_NE(bytes.find("facecap_edit"), std::string::npos);
}

// A benchmark's budget counts the encoder's CPU time: known once the
// writer has waited for its process.
TEST(VideoWriter, TheEncodersCpuTimeIsKnownOnceItHasFinished) {
  TempDir dir;
  VideoWriterOptions o;
  o.width = 320;
  o.height = 240;
  VideoWriter w(dir.path() / "out.mp4", o);
  for (int i = 0; i < 30; ++i) w.write(gradient_frame(i, 320, 240));
  EXPECT_EQ(w.encoder_cpu_ms(), 0.0);
  w.finish();
  EXPECT_GT(w.encoder_cpu_ms(), 0.0);
  EXPECT_LT(w.encoder_cpu_ms(), 60000.0);
}

// The extension picks the container; each carries the marks. Other names
// are refused before anything is written, naming the choices.
TEST(VideoWriter, WritesTheContainerItsNameAsksForWithTheMarks) {
  TempDir dir;
  SyntheticMark mark{"face-swap", "test", {"a.jpg"}, {}};
  VideoWriterOptions o;
  o.width = 64;
  o.height = 48;
  o.metadata = synthetic_metadata(mark);
  for (const char* name : {"out.mp4", "out.M4V", "out.mov", "out.mkv"}) {
    const fs::path out = dir.path() / name;
    {
      VideoWriter w(out, o);
      for (int i = 0; i < 3; ++i) w.write(gradient_frame(i, 64, 48));
      w.finish();
    }
    write_synthetic_sidecar(out, mark);
    EXPECT_EQ(probe_video_file(out).frames, 3) << name;
    EXPECT_TRUE(carries_synthetic_marks(out)) << name;
  }
  EXPECT_EQ(video_container(dir.path() / "out.mkv"), "matroska");
  for (const char* name : {"out.avi", "out.webm", "out"}) {
    try {
      VideoWriter w(dir.path() / name, o);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(".mp4, .m4v, .mov or .mkv"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir.path() / name)) << name;
  }
}

// Frames written at their times on a constant-rate output (25 fps): five in
// their slots, a gap (the fifth frame holds slots 5-9), a frame whose slot
// is taken (dropped), and one more.
TEST(VideoWriter, TimedFramesTakeTheSlotsOfTheirTimes) {
  TempDir dir;
  VideoWriterOptions o;
  o.width = 64;
  o.height = 48;
  o.fps = 25;
  o.encoding.crf = 0;
  const fs::path out = dir.path() / "timed.mp4";
  const std::vector<std::pair<double, int>> written{{10.00, 0},  {10.04, 20},  {10.08, 40},  {10.12, 60},
                                                    {10.16, 80}, {10.40, 100}, {10.41, 120}, {10.44, 140}};
  {
    VideoWriter w(out, o);
    for (const auto& [time, grey] : written) w.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(grey)), time);
    w.finish();
  }
  // Which written frame each output frame shows (the greys are 20 apart; the
  // encoder's colour conversion moves them by a few levels).
  auto video = open_input(out.string());
  std::vector<int> shown;
  for (Frame f; video->read(f);) shown.push_back(int(std::lround(cv::mean(f.image)[0] / 20.0)));
  EXPECT_EQ(shown, (std::vector<int>{0, 1, 2, 3, 4, 4, 4, 4, 4, 4, 5, 7}));
}

// A run stopped early (output_like's max_frames) ends the audio with the
// last frame written, wherever its time puts it: here 30 frames a slot apart
// on the input's timeline, as a variable-rate input gives them, make 59
// frames of video, twice what 30 frames over the rate would say.
TEST(VideoWriter, ARunStoppedEarlyEndsItsAudioWithItsLastFrame) {
  FACECAP_REQUIRE_DATA(source, "address_720p_a.mp4");
  TempDir dir;
  const fs::path out = dir.path() / "cut.mp4";
  const InputInfo input = probe_video_file(source);
  const VideoWriterOptions o = output_like(input, 30);
  {
    VideoWriter w(out, o);
    for (int i = 0; i < 30; ++i) w.write(cv::Mat(o.height, o.width, CV_8UC3, cv::Scalar::all(i * 8)), 2.0 * i / o.fps);
    w.finish();
  }
  const InputInfo info = probe_video_file(out);
  ASSERT_EQ(info.frames, 59);
  ASSERT_TRUE(info.audio);
  // Within one AAC frame (1024 samples, 21-23 ms) and the encoder's padding.
  EXPECT_NEAR(info.audio_duration, 59 / o.fps, 0.05);
  // A run that reads to the input's end keeps the whole track.
  EXPECT_FALSE(output_like(input, input.frames).audio_ends_with_video);
  EXPECT_TRUE(output_like(input, input.frames - 1).audio_ends_with_video);
}

// The frames reach the encoder as YUV 4:2:0 the writer converted: each
// colour comes back as it went in (a swap of the chroma planes turns red
// blue, a wrong range greys every colour), within the 4:2:0 round trip's
// rounding. Patches 16 px square, so the chroma's 2x2 cells lie inside them.
TEST(VideoWriter, ColoursComeBackAsTheyWentIn) {
  TempDir dir;
  VideoWriterOptions o;
  o.width = 96;
  o.height = 32;
  o.encoding.crf = 0;
  const std::vector<cv::Vec3b> colours{{0, 0, 255},    {0, 255, 0},  {255, 0, 0},
                                       {90, 130, 200}, {16, 16, 16}, {235, 235, 235}};
  cv::Mat frame(32, 96, CV_8UC3, cv::Scalar::all(128));
  for (size_t k = 0; k < colours.size(); ++k) frame(cv::Rect(int(k) * 16, 0, 16, 16)).setTo(cv::Scalar(colours[k]));
  const fs::path out = dir.path() / "colours.mp4";
  {
    VideoWriter w(out, o);
    w.write(frame);
    w.finish();
  }
  auto video = open_input(out.string());
  Frame f;
  ASSERT_TRUE(video->read(f));
  for (size_t k = 0; k < colours.size(); ++k) {
    const cv::Scalar back = cv::mean(f.image(cv::Rect(int(k) * 16 + 4, 4, 8, 8)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], colours[k][c], 4.0) << "colour " << k << " channel " << c;
  }
}

TEST(VideoWriter, OddSizesArePaddedForYuv420) {
  TempDir dir;
  VideoWriterOptions o;
  o.width = 101;
  o.height = 75;
  {
    VideoWriter w(dir.path() / "odd.mp4", o);
    for (int i = 0; i < 3; ++i) w.write(gradient_frame(i, 101, 75));
    w.finish();
  }
  EXPECT_EQ(probe_video_file(dir.path() / "odd.mp4").width, 102);
}

TEST(VideoWriter, AnAbandonedWriteKeepsTheOldFileAndLeavesNoPartial) {
  TempDir dir;
  const fs::path out = previous_output(dir);
  VideoWriterOptions o = small_frames();
  {
    VideoWriter w(out, o);
    w.write(gradient_frame(0, 64, 64));
    // destroyed without finish(): an error or an interruption
  }
  EXPECT_TRUE(only_the_previous_output(out));
}

TEST(VideoWriter, UnwritableOutputFolderIsAClearError) {
  VideoWriterOptions o = small_frames();
  try {
    VideoWriter w("/proc/facecap-test/out.mp4", o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/facecap-test"), std::string::npos) << e.what();
  }
}

TEST(VideoWriter, FinishingWithNoFramesIsAnError) {
  TempDir dir;
  VideoWriterOptions o = small_frames();
  VideoWriter w(dir.path() / "none.mp4", o);
  EXPECT_THROW(w.finish(), Error);
  EXPECT_FALSE(fs::exists(dir.path() / "none.mp4"));
}

// x264 settings it lacks are refused before ffmpeg starts, leaving the
// file that was there as it was.
TEST(VideoWriter, EncodingsX264LacksAreAClearError) {
  TempDir dir;
  const fs::path out = previous_output(dir);
  VideoWriterOptions o = small_frames();
  for (const VideoEncoding& bad : {VideoEncoding{52, "veryfast"}, VideoEncoding{-1, "veryfast"},
                                   VideoEncoding{18, "quick"}, VideoEncoding{18, ""}}) {
    o.encoding = bad;
    EXPECT_THROW(VideoWriter(out, o), Error) << bad.crf << " " << bad.preset;
  }
  EXPECT_TRUE(only_the_previous_output(out));
  for (const char* preset : kX264Presets) EXPECT_NO_THROW(check_encoding({0, preset})) << preset;
  EXPECT_NO_THROW(check_encoding({51, "veryslow"}));
}

}  // namespace facecap
