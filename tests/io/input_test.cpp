#include "facecap/io/input.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/command.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "io/damaged_clip.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

std::string open_error(const std::string& spec, double start_seconds = 0) {
  try {
    open_input(spec, start_seconds);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void write_prefix(const fs::path& from, const fs::path& to, double share) {
  const std::string bytes = test::read_file(from);
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
  for (const char* name : {"b.png", "a.png", "c.jpg"}) facecap::write_image((dir.path() / name).string(), img);
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

// A folder is one camera's frames: an image of another size, like one that
// does not decode, is a frame without an image and a reason.
TEST(Input, AFoldersImagesOfAnotherSizeOrCorruptAreFramesWithAReason) {
  TempDir dir;
  facecap::write_image((dir.path() / "a.png").string(), cv::Mat(60, 80, CV_8UC3, cv::Scalar(10, 20, 30)));
  facecap::write_image((dir.path() / "b.png").string(), cv::Mat(80, 60, CV_8UC3, cv::Scalar(10, 20, 30)));
  std::ofstream(dir.path() / "c.png") << "this is not an image\n";
  facecap::write_image((dir.path() / "d.png").string(), cv::Mat(60, 80, CV_8UC3, cv::Scalar(10, 20, 30)));
  auto folder = open_input(dir.path().string());
  std::vector<Frame> frames;
  for (Frame f; folder->read(f);) frames.push_back(f);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_FALSE(frames[0].image.empty());
  EXPECT_TRUE(frames[1].image.empty());
  EXPECT_NE(frames[1].error.find("b.png is 60x80, the folder's first is 80x60"), std::string::npos) << frames[1].error;
  EXPECT_TRUE(frames[2].image.empty());
  EXPECT_NE(frames[2].error.find("cannot decode image"), std::string::npos) << frames[2].error;
  EXPECT_FALSE(frames[3].image.empty());
  EXPECT_TRUE(frames[3].error.empty());
}

// A variable-rate video (frames 10-29 of the webcam clip cut out, the rest
// keeping their timestamps, as a phone's recording keeps its own): each
// frame's time is its timestamp, not its index over the mean rate (frame 10
// would read 0.55 s, 0.65 s before it is shown).
TEST(Input, AVariableRateVideosFramesKeepTheirTimestamps) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const fs::path vfr = dir.path() / "vfr.mp4";
  const test::CommandResult made = test::run_command(
      "ffmpeg -hide_banner -loglevel error -y -i " + webcam.string() +
      " -t 3 -an -vf \"select='not(between(n,10,29))'\" -fps_mode vfr -c:v libx264 -preset ultrafast " + vfr.string() +
      " 2>&1");
  ASSERT_EQ(made.code, 0) << made.out;
  auto source = open_input(vfr.string());
  EXPECT_NEAR(source->info().fps, 55.0 / 3.0, 0.01);  // the mean rate: 55 frames in 3 s
  std::vector<Frame> frames;
  for (Frame f; source->read(f);) frames.push_back(f);
  ASSERT_EQ(frames.size(), 55u);
  for (const auto& [index, seconds] : std::vector<std::pair<int, double>>{{0, 0.0}, {9, 0.36}, {10, 1.2}, {54, 2.96}}) {
    EXPECT_EQ(frames[size_t(index)].index, index);
    EXPECT_NEAR(frames[size_t(index)].time, seconds, 1e-3) << "frame " << index;
  }
  // Starting part-way gives the first frame at or after the time, wherever
  // the mean rate guesses it (for 1.0 s frame 19, at 1.56 s; for 0.37 s
  // frame 7, at 0.28 s).
  for (const auto& [start, first] : std::vector<std::pair<double, int>>{{0.2, 5}, {0.37, 10}, {1.0, 10}, {1.3, 13}}) {
    auto part = open_input(vfr.string(), start);
    Frame f;
    ASSERT_TRUE(part->read(f)) << start;
    EXPECT_EQ(f.index, first) << start;
    EXPECT_NEAR(f.time, frames[size_t(first)].time, 1e-9) << start;
    EXPECT_NEAR(start_time(part->info()), f.time, 1e-9) << start;
    EXPECT_EQ(cv::norm(f.image, frames[size_t(first)].image, cv::NORM_INF), 0.0) << start;
  }
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
  // No camera 99: libavdevice's input names it (or says the library is missing).
  EXPECT_NE(open_error("cam:99").find("camera 99"), std::string::npos) << open_error("cam:99");
  EXPECT_NE(open_error("").find("no input"), std::string::npos);
}

// A video cut short: with its index (moov) at the end, the cut file has none
// and is refused by name; with its index first, as a download that stopped
// leaves it, it is read to the cut, as `ffprobe -count_frames` reads it, and
// early_end() says how many of the frames its index lists lie past the end.
// Cut before its first frame, it is refused saying so.
TEST(Input, AVideoCutShortIsReadToTheCutWhereItsIndexComesFirst) {
  TempDir dir;
  FACECAP_REQUIRE_DATA(address, "address_720p_a.mp4");
  write_prefix(address, dir.path() / "cut_a.mp4", 0.5);
  const std::string a = open_error((dir.path() / "cut_a.mp4").string());
  EXPECT_NE(a.find("cut_a.mp4"), std::string::npos) << a;

  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  const fs::path cut = dir.path() / "cut_b.mp4";
  write_prefix(webcam, cut, 0.4);
  const int ffprobe_frames = test::ffprobe_frames_decoded(cut);
  auto source = open_input(cut.string());
  const int listed = source->info().frames;
  EXPECT_EQ(listed, 1337);  // what the index lists, as the whole file's
  int frames = 0;
  for (Frame f; source->read(f); ++frames) EXPECT_FALSE(f.image.empty()) << f.index;
  EXPECT_EQ(frames, ffprobe_frames);
  EXPECT_GT(frames, listed / 4);
  EXPECT_LT(frames, listed / 2);
  // The packet cut part-way is refused or decoded with damage; the rest lie past the end.
  const int unread = listed - frames - source->refused_packets();
  EXPECT_EQ(source->info().frames_past_end, unread);  // known on opening, from the index
  EXPECT_EQ(source->early_end(), "the file is cut short: the last " + std::to_string(unread) + " of the " +
                                     std::to_string(listed) + " frames its index lists lie past its end");

  for (const double share : {0.0129, 0.0135}) {  // just before the first packet, and part-way into it
    write_prefix(webcam, dir.path() / "cut_c.mp4", share);
    const std::string c = open_error((dir.path() / "cut_c.mp4").string());
    EXPECT_NE(c.find("cut_c.mp4: no frame could be decoded (the file is cut short: the last 13"), std::string::npos)
        << c;
  }
}

// A stream damaged part-way decodes on, frame by frame, and a frame decoded
// with its damage concealed says so (Frame::damaged), so that a capture can
// tell a corrupt video from one where no face shows (damaged_clip.hpp: the
// first keyframe hit).
TEST(Input, AFrameDecodedWithDamageIsFlagged) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  const auto read_all = [](const fs::path& video) {
    std::vector<int> damaged;
    int frames = 0;
    auto source = open_input(video.string());
    for (Frame f; source->read(f); ++frames) {
      EXPECT_FALSE(f.image.empty()) << f.index;
      if (f.damaged) damaged.push_back(f.index);
    }
    return std::pair{frames, damaged};
  };
  const auto [clean_frames, clean_damaged] = read_all(clip.clean);
  const auto [hit_frames, hit_damaged] = read_all(clip.damaged);
  EXPECT_EQ(clean_frames, test::DamagedClip::kFrames);
  EXPECT_TRUE(clean_damaged.empty());
  EXPECT_EQ(hit_frames, clean_frames);  // the damaged frame and those predicted from it still come
  EXPECT_EQ(hit_damaged, std::vector<int>{0});
}

// A video whose index is damaged part-way (damaged_clip.hpp) ends where the
// demuxer stops, as ffmpeg's does, but not silently: once read() has returned
// false, early_end() says how many of the frames the index lists were never
// reached, from the start or after a seek. A whole video says nothing.
TEST(Input, AVideoEndingShortOfItsIndexSaysHowManyFramesWentUnread) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  const auto read_to_end = [](const fs::path& video, double start) {
    auto source = open_input(video.string(), start);
    int frames = 0;
    for (Frame f; source->read(f); ++frames) EXPECT_FALSE(f.image.empty()) << f.index;
    return std::pair{frames, source->early_end()};
  };
  const std::string expected = test::DamagedClip::damaged_index_early_end();
  const auto [frames, early_end] = read_to_end(clip.damaged_index, 0);
  EXPECT_EQ(frames, test::DamagedClip::kIndexDamagedAt);
  EXPECT_EQ(early_end, expected);
  const auto [later_frames, later_early_end] = read_to_end(clip.damaged_index, 0.4);  // frame 10 on
  EXPECT_EQ(later_frames, test::DamagedClip::kIndexDamagedAt - 10);
  EXPECT_EQ(later_early_end, expected);
  EXPECT_EQ(read_to_end(clip.clean, 0).second, "");
  EXPECT_EQ(read_to_end(clip.clean, 0.4).second, "");
  for (const char* name : {"address_720p_a.mp4", "emotions_pexels_640x360.mp4"}) {
    FACECAP_REQUIRE_DATA(video, name);
    EXPECT_EQ(read_to_end(video, 0).second, "") << name;
  }
  // Not a video: nothing to say.
  FACECAP_REQUIRE_DATA(photo, "portrait_obama.jpg");
  EXPECT_EQ(read_to_end(photo, 0).second, "");
}

// A transport stream cut from the middle of another, with no keyframe and
// so no stream headers after the cut (a recording joined late), has no
// picture to give: refused in one line that says why, not taken for a video
// without a face.
TEST(Input, AStreamCutFromTheMiddleWithoutItsHeadersSaysWhy) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());  // one keyframe, at its start
  const fs::path whole = dir.path() / "whole.ts";
  const test::CommandResult made = test::run_command("ffmpeg -hide_banner -loglevel error -y -i " +
                                                     clip.clean.string() + " -c copy " + whole.string() + " 2>&1");
  ASSERT_EQ(made.code, 0) << made.out;
  const std::string bytes = test::read_file(whole);
  constexpr size_t kTsPacket = 188;
  const size_t kept = bytes.size() / 2 / kTsPacket * kTsPacket;  // the second half, whole packets
  std::ofstream(dir.path() / "late.ts", std::ios::binary) << bytes.substr(bytes.size() - kept);
  const std::string e = open_error((dir.path() / "late.ts").string());
  EXPECT_NE(e.find("late.ts: its video has no frame size (no picture in it could be decoded"), std::string::npos) << e;
}

// Packets the decoder refuses (damaged_clip.hpp: a sample size 4 bytes
// short, so the packets after it in its chunk are misread) are counted as
// `ffmpeg` counts its decode errors, from the start or after a seek; the
// frames before them still come, and the stream reads to its end. A whole
// video, or one decoded with damage concealed, counts none.
TEST(Input, PacketsTheDecoderRefusesAreCountedAsFfmpegCountsThem) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  struct Read {
    int frames = 0;
    int refused = 0;
    std::string early_end;
  };
  const auto read_to_end = [](const fs::path& video, double start) {
    auto source = open_input(video.string(), start);
    Read read;
    for (Frame f; source->read(f); ++read.frames) EXPECT_FALSE(f.image.empty()) << f.index;
    read.refused = source->refused_packets();
    read.early_end = source->early_end();
    return read;
  };
  const test::CommandResult ffmpeg = test::run_command("ffmpeg -hide_banner -nostats -loglevel repeat+error -i " +
                                                       clip.misaligned.string() + " -f null - 2>&1");
  ASSERT_EQ(ffmpeg.code, 0) << ffmpeg.out;
  int ffmpeg_errors = 0;
  for (size_t at = 0; (at = ffmpeg.out.find("Error while decoding", at)) != std::string::npos; ++at) ++ffmpeg_errors;
  const Read misaligned = read_to_end(clip.misaligned, 0);
  EXPECT_GT(misaligned.refused, 20);  // most of the packets after the misaligned one
  EXPECT_EQ(misaligned.refused, ffmpeg_errors);
  EXPECT_EQ(misaligned.frames, test::DamagedClip::kIndexDamagedAt);
  EXPECT_EQ(misaligned.frames + misaligned.refused, test::DamagedClip::kFrames);  // each refused packet a lost frame
  EXPECT_EQ(misaligned.early_end, "");                                            // every packet was read
  const Read later = read_to_end(clip.misaligned, 0.4);                           // frame 10 on
  EXPECT_EQ(later.frames, test::DamagedClip::kIndexDamagedAt - 10);
  EXPECT_EQ(later.refused, misaligned.refused);
  for (const fs::path& whole : {clip.clean, clip.damaged}) EXPECT_EQ(read_to_end(whole, 0).refused, 0) << whole;
  // Every packet refused: no frame to open with, and the error counts them.
  const std::string none = open_error(clip.shifted.string());
  EXPECT_NE(none.find("shifted.mp4: no frame could be decoded (the decoder refused " +
                      std::to_string(test::DamagedClip::kFrames) + " packet(s) of it: a corrupt stream"),
            std::string::npos)
      << none;
}

// Starting part-way gives exactly the frames a read from the start gives
// there, with their own indices and times.
TEST(Input, StartingPartWayGivesTheFramesOfASequentialRead) {
  for (const char* name : {"talking_webcam_400x300.mp4", "address_720p_a.mp4"}) {
    FACECAP_REQUIRE_DATA(video, name);
    auto whole = open_input(video.string());
    const double fps = whole->info().fps;
    ASSERT_GT(fps, 0.0);
    std::vector<cv::Mat> frames;
    for (Frame f; frames.size() < 80 && whole->read(f);) frames.push_back(f.image.clone());
    ASSERT_EQ(frames.size(), 80u);
    // At a frame's time, and just after it (the next frame is the first at or
    // after); frames between keyframes and at the clip's start.
    for (const auto& [seconds, first] :
         std::vector<std::pair<double, int>>{{50 / fps, 50}, {50.5 / fps, 51}, {7 / fps, 7}, {0.5 / fps, 1}}) {
      auto part = open_input(video.string(), seconds);
      EXPECT_EQ(part->info().first_frame, first);
      for (int k = 0; k < 3; ++k) {
        Frame f;
        ASSERT_TRUE(part->read(f));
        EXPECT_EQ(f.index, first + k);
        EXPECT_NEAR(f.time, (first + k) / fps, 1e-9);
        EXPECT_EQ(cv::norm(f.image, frames[size_t(first + k)], cv::NORM_INF), 0.0) << name << " frame " << first + k;
      }
    }
  }
}

TEST(Input, AStartPastTheEndOrWithoutATimelineIsAClearError) {
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(image, "portrait_obama.jpg");
  EXPECT_NE(open_error(video.string(), 1000).find("long"), std::string::npos) << open_error(video.string(), 1000);
  EXPECT_NE(open_error(video.string(), -1).find("0 or more"), std::string::npos);
  EXPECT_NE(open_error(image.string(), 1).find("only a video file"), std::string::npos);
  EXPECT_NE(open_error(image.parent_path().string(), 1).find("only a video file"), std::string::npos);
  EXPECT_EQ(open_error(image.string(), 0), "");  // no start: any input
}

// Every frame of three clips decodes to exactly what OpenCV's FFmpeg back-end
// gave before it was replaced (it is no longer linked): the sums of their
// channels over the whole clip, measured with OpenCV 4.6's VideoCapture.
TEST(Input, ClipsDecodeToWhatOpenCvsBackEndGave) {
  const std::vector<std::tuple<std::string, int, cv::Scalar>> expected = {
      {"address_720p_a.mp4", 144, cv::Scalar(7733607356., 9736959717., 14061497345.)},
      {"talking_webcam_400x300.mp4", 1337, cv::Scalar(18936911417., 22246652366., 24373590295.)},
      {"emotions_pexels_640x360.mp4", 472, cv::Scalar(6135924949., 6619518388., 7889616137.)}};
  for (const auto& [name, frames, sums] : expected) {
    FACECAP_REQUIRE_DATA(video, name);
    auto source = open_input(video.string());
    cv::Scalar ours;
    int count = 0;
    for (Frame f; source->read(f); ++count) ours += cv::sum(f.image);
    EXPECT_EQ(count, frames) << name;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(ours[c], sums[c]) << name << " channel " << c;
  }
}

// A phone's portrait clip stores landscape frames and a display matrix;
// its frames come out turned upright, as players show them.
TEST(Input, ARotatedClipsFramesComeOutUpright) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  auto plain = open_input(webcam.string());
  std::vector<cv::Mat> originals;
  for (Frame f; originals.size() < 5 && plain->read(f);) originals.push_back(f.image.clone());
  for (const auto& [degrees, rotation] : std::vector<std::pair<int, int>>{
           {90, cv::ROTATE_90_CLOCKWISE}, {180, cv::ROTATE_180}, {270, cv::ROTATE_90_COUNTERCLOCKWISE}}) {
    const fs::path turned = dir.path() / ("turned" + std::to_string(degrees) + ".mp4");
    const test::CommandResult made = test::run_command("ffmpeg -hide_banner -loglevel error -y -i " + webcam.string() +
                                                       " -t 1 -c copy -metadata:s:v rotate=" + std::to_string(degrees) +
                                                       " " + turned.string() + " 2>&1");
    ASSERT_EQ(made.code, 0) << made.out;
    auto source = open_input(turned.string());
    EXPECT_EQ(source->info().width, degrees == 180 ? 400 : 300) << degrees;
    for (const cv::Mat& original : originals) {
      Frame f;
      ASSERT_TRUE(source->read(f));
      cv::Mat expected;
      cv::rotate(original, expected, rotation);
      ASSERT_EQ(f.image.size(), expected.size()) << degrees;
      EXPECT_EQ(cv::norm(f.image, expected, cv::NORM_INF), 0.0) << degrees;
    }
  }
}

}  // namespace facecap
