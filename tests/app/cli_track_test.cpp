// facecap track and probe end to end: bad inputs, faces not found, several
// faces, damaged videos and folders, and the streamed and tabled outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_support.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/marked_image.hpp"
#include "facecap/io/png16.hpp"
#include "io/damaged_clip.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(Cli, TrackRejectsBadInputsAndOutputsWithOneLine) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  std::ofstream(dir.path() / "text.mp4") << "not a video";
  RunResult r = run("track " + (dir.path() / "text.mp4").string() + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "frames.csv"));
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  r = run("track " + video.string() + " -o /proc/facecap-test");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/proc/facecap-test"), std::string::npos) << r.out;
  // An --identity file that is missing, not an identity, or of another
  // model's size is named in one line, and nothing is written.
  std::ofstream(dir.path() / "short.json") << R"({"identity_weights": [0.1, 0.2]})";
  for (const char* file : {"missing.json", "text.mp4", "short.json"}) {
    r = run("track " + video.string() + " -o " + (dir.path() / "out").string() + " --identity " +
            (dir.path() / file).string());
    EXPECT_EQ(r.code, 1) << file << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find("identit"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "frames.csv")) << file;
  }
  // A start before 0 or not a number is named; one past the end, or into an
  // image, is a one-line error that writes nothing.
  for (const char* start : {"-1", "soon"}) {
    r = run("track " + video.string() + " -o " + (dir.path() / "out").string() + " --start " + start);
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.out.find("--start"), std::string::npos) << r.out;
  }
  FACECAP_REQUIRE_DATA(image, "portrait_obama.jpg");
  for (const std::string& input : {video.string() + " --start 3600", image.string() + " --start 1"}) {
    r = run("track " + input + " -o " + (dir.path() / "out").string());
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find("cannot start"), std::string::npos) << r.out;
  }
  // A Live Link host that cannot be found is named, before any work.
  r = run("track " + video.string() + " -o " + (dir.path() / "out").string() +
          " --livelink-udp no-such-host.invalid:11111");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("no-such-host.invalid"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "frames.csv"));
}

// Where the folder of per-frame files (--aligned-faces' `aligned`,
// --detail-maps' `detail`, --uv-pass' `uv`) is a file, the run stops before any frame in one
// line naming it, leaves the file as it was and writes no table.
TEST(Cli, TrackRefusesAPerFrameFolderThatIsAFile) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  for (const auto& [folder, options] : {std::pair<const char*, const char*>{"aligned", "--aligned-faces"},
                                        std::pair<const char*, const char*>{"detail", "--refine --detail-maps"},
                                        std::pair<const char*, const char*>{"uv", "--uv-pass"}}) {
    TempDir dir;
    std::ofstream(dir.path() / folder) << "mine";
    const RunResult r = run("track " + video.string() + " --max-frames 2 " + options + " -o " + dir.path().string());
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find((dir.path() / folder).string()), std::string::npos) << r.out;
    EXPECT_EQ(test::read_file(dir.path() / folder), "mine");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
    EXPECT_EQ(entries, 1) << folder << ": only the file is there";
  }
}

TEST(Cli, TrackOfAnImageWithNoFaceIsAnErrorThatSaysSo) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const auto image = dir.path() / "grey.ppm";
  {
    std::ofstream f(image, std::ios::binary);
    f << "P6 320 240 255\n" << std::string(320 * 240 * 3, char(128));
  }
  std::filesystem::create_directories(dir.path() / "out");
  std::ofstream(dir.path() / "out" / "identity.json") << "{}";         // an earlier run's
  std::ofstream(dir.path() / "out" / "animation.glb") << "glTF";       // an earlier run's
  std::ofstream(dir.path() / "out" / "face_matte.png") << "PNG";       // an earlier run's
  std::ofstream(dir.path() / "out" / "head.chan") << "1 0 0 0 0 0 0";  // an earlier run's
  const RunResult r = run("track " + image.string() + " -o " + (dir.path() / "out").string() + " --gltf --chan");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("no face found in " + image.string()), std::string::npos) << r.out;
  // The per-frame record is complete: one frame, lost.
  std::ifstream csv(dir.path() / "out" / "frames.csv");
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  EXPECT_EQ(row.rfind("0,0,lost,", 0), 0u) << row;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "identity.json"));   // no identity was seen here
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "animation.glb"));   // nor a face to animate
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "face_matte.png"));  // nor to matte
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "head.chan"));       // nor a motion to key
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "camera.chan"));
}

// track --each-image: a folder where no image shows a face is an error that
// says so in one line, after the table that gives each image's status; the
// option is for folders and for one face an image, and says so otherwise.
TEST(Cli, TrackEachImageSaysWhenNoImageHasAFace) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const fs::path folder = dir.path() / "images";
  fs::create_directories(folder);
  write_image((folder / "grey.png").string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar::all(128)));
  std::ofstream(folder / "broken.jpg") << "not a jpeg";
  const fs::path out = dir.path() / "out";
  const RunResult r = run("track " + folder.string() + " -o " + out.string() + " --each-image");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("no face found in any of the 2 image(s)"), std::string::npos) << r.out;
  std::ifstream csv(out / "images.csv");
  std::string header, broken, grey;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, broken) && std::getline(csv, grey));
  EXPECT_EQ(broken.rfind("broken.jpg,error,", 0), 0u) << broken;
  EXPECT_EQ(grey.rfind("grey.png,lost,", 0), 0u) << grey;

  for (const std::string& bad : {"track " + folder.string() + " -o " + out.string() + " --each-image --all-faces",
                                 "track " + folder.string() + " -o " + out.string() + " --each-image --start 1",
                                 "track " + folder.string() + " -o " + out.string() + " --mesh-format ply"}) {
    const RunResult usage = run(bad);
    EXPECT_EQ(usage.code, 2) << bad << ": " << usage.out;
  }
}

TEST(Cli, ProbeDescribesAVideoAsJson) {
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  const RunResult r = run("probe " + video.string());
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("\"width\": 1280"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"audio\": true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 1"), std::string::npos) << r.out;
}

// A video cut short after its index (damaged_clip.hpp's clean clip, its
// first 60 %): probe counts the frames its index lists past the end, which
// with those `ffprobe -count_frames` decodes make up the whole (the packet
// the cut splits aside); a whole video has no such count.
TEST(Cli, ProbeCountsTheFramesACutShortVideoListsPastItsEnd) {
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  const std::string bytes = test::read_file(clip.clean);
  const fs::path cut = dir.path() / "cut.mp4";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 6 / 10);
  const nlohmann::json probe = json_from("probe " + cut.string());
  const int decoded = test::ffprobe_frames_decoded(cut);
  EXPECT_EQ(probe.value("frames", 0), test::DamagedClip::kFrames);
  const int past_end = probe.value("frames_past_end", 0);
  EXPECT_GT(past_end, 0);
  EXPECT_GE(decoded + past_end, test::DamagedClip::kFrames - 1);
  EXPECT_LE(decoded + past_end, test::DamagedClip::kFrames);
  EXPECT_FALSE(json_from("probe " + clip.clean.string()).contains("frames_past_end"));
}

// dlib's face detector is decoded once (0.3 s) and kept in the cache folder
// in dlib's plain form (read back in 2-3 ms): later runs find the same faces;
// a damaged cache file is decoded again and rewritten; a cache folder that
// cannot be written costs only the time.
TEST(Cli, TheFaceDetectorIsKeptInTheCacheAndADamagedCopyIsRebuilt) {
  FACECAP_REQUIRE_DATA(image, "lfpw_image_0010.png");
  TempDir dir;
  const fs::path cache = dir.path() / "cache";
  const auto probe = [&](const fs::path& cache_dir) {
    return test::run_command("FACECAP_CACHE_DIR=" + cache_dir.string() + " " + std::string(FACECAP_BINARY) +
                             " -q probe " + image.string() + " 2>&1");
  };
  const RunResult first = probe(cache);
  ASSERT_EQ(first.code, 0) << first.out;
  EXPECT_NE(first.out.find("\"faces\": 1"), std::string::npos) << first.out;
  std::vector<fs::path> kept;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().filename().string().starts_with("dlib-frontal-face-detector-")) kept.push_back(e.path());
  ASSERT_EQ(kept.size(), 1u);
  const auto size = fs::file_size(kept[0]);
  EXPECT_GT(size, 10000u);
  const RunResult second = probe(cache);
  EXPECT_EQ(second.code, 0);
  EXPECT_EQ(second.out, first.out);
  fs::resize_file(kept[0], 100);  // a truncated copy
  const RunResult third = probe(cache);
  EXPECT_EQ(third.code, 0);
  EXPECT_EQ(third.out, first.out);
  EXPECT_EQ(fs::file_size(kept[0]), size);
  std::ofstream(dir.path() / "not_a_folder") << "x";
  const RunResult unwritable = probe(dir.path() / "not_a_folder");
  EXPECT_EQ(unwritable.code, 0);
  EXPECT_EQ(unwritable.out, first.out);
}

// A wide shot: Obama's portrait at a quarter of its size on a grey 1280x720
// frame, his face about 90 px wide (36 px between the outer eye corners),
// half what the detector finds in a frame downscaled to 640 px. Both probe
// and track find it by searching again at twice the size.
TEST(Cli, ProbeAndTrackFindAFaceInAWideShot) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(portrait, "portrait_obama.jpg");
  const cv::Mat photo = facecap::read_image(portrait.string());
  ASSERT_FALSE(photo.empty());
  cv::Mat small;
  cv::resize(photo, small, cv::Size(), 0.25, 0.25, cv::INTER_AREA);
  cv::Mat wide(720, 1280, CV_8UC3, cv::Scalar(120, 120, 120));
  small.copyTo(wide(cv::Rect(700, 300, small.cols, small.rows)));
  TempDir dir;
  const auto image = dir.path() / "wide.png";
  facecap::write_image(image.string(), wide);
  RunResult r = run("probe " + image.string());
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 1"), std::string::npos) << r.out;
  r = run("track " + image.string() + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream csv(dir.path() / "out" / "frames.csv");
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  EXPECT_EQ(row.find(",lost,"), std::string::npos) << row;
}

// A video whose stream is damaged past its first frames: its frames decode
// with their damage and are tracked or lost, and libav's line per broken
// macroblock ("[h264 @ ...] error while decoding MB") stays out of the output;
// one line of facecap's own says how many frames came with damage, and
// frames.jsonl marks them ("damaged": true).
TEST(Cli, ADamagedVideoIsTrackedWithoutTheDecodersChatter) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  std::ifstream in(video, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t i = 60000; i + 1 < bytes.size() && i < 400000; i += 2000) bytes[i] = char(~bytes[i]);
  const auto damaged = dir.path() / "damaged.mp4";
  std::ofstream(damaged, std::ios::binary) << bytes;
  const RunResult r = run("track " + damaged.string() + " -o " + (dir.path() / "out").string() + " --max-frames 120");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("error while decoding"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("[h264"), std::string::npos) << r.out;
  EXPECT_LE(lines(r.out), 4) << r.out;
  int marked = 0, rows = 0;
  for (const std::string& line : test::read_lines(dir.path() / "out" / "frames.jsonl")) {
    ++rows;
    marked += nlohmann::json::parse(line).value("damaged", false);
  }
  EXPECT_EQ(rows, 120);
  EXPECT_GT(marked, 0);
  EXPECT_LT(marked, 120);
  EXPECT_NE(r.out.find("facecap: " + std::to_string(marked) + " frame(s) of " + damaged.string() +
                       " were decoded with damage"),
            std::string::npos)
      << r.out;
}

namespace {

// A damaged video's track, alone, with what it printed and the rows it wrote.
struct DamagedTrack {
  std::string out;
  size_t rows = 0;
};

// Tracks `video` alone and with --all-faces (into DIR/one and DIR/all): both
// succeed and print `note(what)`, `what` the video alone and "the input"
// with --all-faces.
DamagedTrack track_alone_and_all_faces(const fs::path& video, const fs::path& dir,
                                       const std::function<std::string(const std::string& what)>& note) {
  const RunResult one = run("track " + video.string() + " -o " + (dir / "one").string());
  EXPECT_EQ(one.code, 0) << one.out;
  EXPECT_NE(one.out.find(note(video.string())), std::string::npos) << one.out;
  const RunResult all = run("track " + video.string() + " -o " + (dir / "all").string() + " --all-faces");
  EXPECT_EQ(all.code, 0) << all.out;
  EXPECT_NE(all.out.find(note("the input")), std::string::npos) << all.out;
  return {one.out, test::read_lines(dir / "one" / "frames.jsonl").size()};
}

}  // namespace

// A video ending short of its index (damaged_clip.hpp: libavformat stops at
// a damaged entry, as ffmpeg does) is tracked to where it ends, and one line
// says how many frames went unread, alone and with --all-faces.
TEST(Cli, AVideoEndingShortOfItsIndexIsTrackedToItsEndAndSaysSo) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  const DamagedTrack track = track_alone_and_all_faces(clip.damaged_index, dir.path(), [](const std::string& what) {
    return "facecap: " + what + " ends early: " + test::DamagedClip::damaged_index_early_end() + "\n";
  });
  EXPECT_EQ(track.rows, size_t(test::DamagedClip::kIndexDamagedAt));
  const RunResult clean = run("track " + clip.clean.string() + " -o " + (dir.path() / "clean").string());
  EXPECT_EQ(clean.code, 0) << clean.out;
  EXPECT_EQ(clean.out.find("ends early"), std::string::npos) << clean.out;
}

// Packets the decoder refuses (damaged_clip.hpp: a misaligned sample) are
// counted in one line, alone and with --all-faces: their frames are lost
// with no row of their own, the rows' times keeping the gap.
TEST(Cli, PacketsTheDecoderRefusesAreCountedInOneLine) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  TempDir dir;
  const test::DamagedClip clip = test::write_damaged_clip(webcam, dir.path());
  const int refused = test::DamagedClip::kFrames - test::DamagedClip::kIndexDamagedAt;
  const DamagedTrack track = track_alone_and_all_faces(clip.misaligned, dir.path(), [&](const std::string& what) {
    return "the decoder refused " + std::to_string(refused) + " packet(s) of " + what +
           " (a corrupt stream: their frames are lost";
  });
  EXPECT_EQ(track.out.find("ends early"), std::string::npos) << track.out;
  EXPECT_EQ(track.rows, size_t(test::DamagedClip::kIndexDamagedAt));
}

// A folder of photos of different sizes is not one camera's frames: the
// photos unlike the first are lost, each with its reason in frames.jsonl,
// and the closing summary says so in one line. Output videos keep the frame,
// black (an edit of the folder failed on it with an OpenCV assertion).
TEST(Cli, TrackSaysWhichFramesOfAFolderCouldNotBeRead) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(biden, "portrait_biden.jpg");
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "photos");
  std::filesystem::copy_file(obama, dir.path() / "photos" / "1.jpg");
  std::filesystem::copy_file(biden, dir.path() / "photos" / "2.jpg");
  const RunResult r = test::run_command(std::string(FACECAP_BINARY) + " track " + (dir.path() / "photos").string() +
                                        " -o " + (dir.path() / "out").string() + " --overlay 2>&1 >/dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("facecap: 1 frame(s) of " + (dir.path() / "photos").string() + " could not be read"),
            std::string::npos)
      << r.out;
  std::ifstream jsonl(dir.path() / "out" / "frames.jsonl");
  std::string line;
  std::vector<nlohmann::json> rows;
  while (std::getline(jsonl, line)) rows.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NE(rows[0]["status"], "lost");
  EXPECT_FALSE(rows[0].contains("error"));
  EXPECT_EQ(rows[1]["status"], "lost");
  EXPECT_NE(rows[1].value("error", "").find("2.jpg is 970x2204, the folder's first is 910x1137"), std::string::npos)
      << rows[1].dump();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / "overlay.mp4"));
  const auto edited = dir.path() / "edited.mp4";
  const RunResult t = run("transform " + (dir.path() / "photos").string() + " --to happiness -o " + edited.string());
  EXPECT_EQ(t.code, 0) << t.out;
  EXPECT_NE(t.out.find("1 frame(s) of"), std::string::npos) << t.out;
  EXPECT_TRUE(std::filesystem::exists(edited));
}

// Two faces side by side (Obama's portrait, 72 px between the eye corners,
// and Biden's, 115 px): the larger is tracked, and the summary says there
// were two.
namespace {

// Obama's portrait (72 px between the eye corners) and Biden's (115 px),
// side by side; `left_width`: where Biden's begins.
cv::Mat two_portraits(const fs::path& obama, const fs::path& biden, int& left_width) {
  cv::Mat left = facecap::read_image(obama.string()), right = facecap::read_image(biden.string());
  if (left.empty() || right.empty()) return {};
  cv::resize(right(cv::Rect(0, 0, right.cols, 800)), right, cv::Size(), 0.7, 0.7, cv::INTER_AREA);
  cv::resize(left, left, cv::Size(left.cols * right.rows / left.rows, right.rows), 0, 0, cv::INTER_AREA);
  cv::Mat both;
  cv::hconcat(left, right, both);
  left_width = left.cols;
  return both;
}

// The faces `probe` lists in `image` (its face_boxes; empty where it failed).
nlohmann::json probed_face_boxes(const fs::path& image) {
  const RunResult p = test::run_command(std::string(FACECAP_BINARY) + " -q probe " + image.string());
  EXPECT_EQ(p.code, 0) << p.out;
  if (p.code != 0) return nlohmann::json::array();
  return nlohmann::json::parse(p.out)["face_boxes"];
}

// A face box's centre as --face takes it: "X,Y".
std::string face_point(const nlohmann::json& box) {
  return std::to_string(box["centre"][0].get<int>()) + "," + std::to_string(box["centre"][1].get<int>());
}

// The first frame's landmark `index` in a track's frames.jsonl.
Vec2f first_landmark(const fs::path& out, int index) {
  std::ifstream jsonl(out / "frames.jsonl");
  std::string line;
  std::getline(jsonl, line);
  const nlohmann::json p = nlohmann::json::parse(line)["landmarks"][index];
  return {p[0].get<float>(), p[1].get<float>()};
}

}  // namespace

TEST(Cli, TrackSaysWhenMoreThanOneFaceIsInView) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(biden, "portrait_biden.jpg");
  int left_width = 0;
  const cv::Mat both = two_portraits(obama, biden, left_width);
  ASSERT_FALSE(both.empty());
  TempDir dir;
  const auto image = dir.path() / "two.png";
  facecap::write_image(image.string(), both);
  const RunResult r = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                        (dir.path() / "out").string() + " 2>&1 >/dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("up to 2 faces in view; one is tracked per run (--face chooses which"), std::string::npos)
      << r.out;
  auto nose_x = [&](const fs::path& out) { return first_landmark(out, 30).x(); };
  EXPECT_GT(nose_x(dir.path() / "out"), left_width) << "the nose tip of the larger face, on the right";
  // --face picks the other one.
  const RunResult l = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                        (dir.path() / "left").string() + " --face left 2>&1 >/dev/null");
  ASSERT_EQ(l.code, 0) << l.out;
  EXPECT_LT(nose_x(dir.path() / "left"), left_width) << "the nose tip of the face on the left";
  // probe says where the faces are, left to right; a centre is a --face X,Y.
  const nlohmann::json boxes = probed_face_boxes(image);
  ASSERT_EQ(boxes.size(), 2u) << boxes;
  EXPECT_LT(boxes[0]["centre"][0].get<int>(), left_width);
  EXPECT_GT(boxes[1]["centre"][0].get<int>(), left_width);
  const std::string at = face_point(boxes[0]);
  const RunResult point = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                            (dir.path() / "point").string() + " --face " + at + " 2>&1 >/dev/null");
  ASSERT_EQ(point.code, 0) << point.out;
  EXPECT_LT(nose_x(dir.path() / "point"), left_width) << "the face at " << at;
  // --all-faces: both, each into its own folder, left to right.
  const RunResult all = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                          (dir.path() / "all").string() + " --all-faces 2>&1 >/dev/null");
  ASSERT_EQ(all.code, 0) << all.out;
  EXPECT_LT(nose_x(dir.path() / "all" / "face_0"), left_width);
  EXPECT_GT(nose_x(dir.path() / "all" / "face_1"), left_width);
  EXPECT_NE(all.out.find("2 face(s) in 1 frames, one decoding pass"), std::string::npos) << all.out;
  // transform --all-faces: the left one smiles and the right one looks sad
  // (--face-to) in the one marked image; a face the photo does not show is
  // said to be missing.
  const fs::path smiles = dir.path() / "smiles.png";
  const RunResult happy =
      test::run_command(std::string(FACECAP_BINARY) + " transform " + image.string() + " -o " + smiles.string() +
                        " --to happiness --all-faces --face-to 1=sadness --face-to 4=anger 2>&1");
  ASSERT_EQ(happy.code, 0) << happy.out;
  EXPECT_NE(happy.out.find("face 0 (from frame 0): frames 1, transformed 1, lost 0\n"), std::string::npos) << happy.out;
  EXPECT_NE(happy.out.find("face 1 (from frame 0): frames 1, transformed 1, lost 0 (neutral to sadness)"),
            std::string::npos)
      << happy.out;
  EXPECT_NE(happy.out.find("face 4 (--face-to, --face-schedule) was not found: the input showed 2 face(s)"),
            std::string::npos)
      << happy.out;
  const cv::Mat changed = facecap::read_image(smiles.string());
  ASSERT_EQ(changed.size(), both.size());
  EXPECT_TRUE(fs::exists(smiles.string() + ".json"));
  const cv::Rect left_part(0, 0, left_width, both.rows), right_part(left_width, 0, both.cols - left_width, both.rows);
  EXPECT_GT(cv::norm(changed(left_part), both(left_part), cv::NORM_INF), 40.0);
  EXPECT_GT(cv::norm(changed(right_part), both(right_part), cv::NORM_INF), 40.0);
  // swap --all-faces: Biden's face on the left one, Obama's (--face-source)
  // on the right one.
  const fs::path swapped = dir.path() / "swapped.png";
  const RunResult swap = test::run_command(std::string(FACECAP_BINARY) + " swap --source " + biden.string() +
                                           " --target " + image.string() + " -o " + swapped.string() +
                                           " --all-faces --face-source 1=" + obama.string() + " 2>&1");
  ASSERT_EQ(swap.code, 0) << swap.out;
  EXPECT_NE(swap.out.find("face 1 (from frame 0): frames 1, swapped 1, lost 0 (the face from " + obama.string() + ")"),
            std::string::npos)
      << swap.out;
  const cv::Mat swapped_image = facecap::read_image(swapped.string());
  ASSERT_EQ(swapped_image.size(), both.size());
  EXPECT_GT(cv::norm(swapped_image(left_part), both(left_part), cv::NORM_INF), 40.0);
  EXPECT_GT(cv::norm(swapped_image(right_part), both(right_part), cv::NORM_INF), 40.0);
  const RunResult bad = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                          (dir.path() / "bad").string() + " --face middle 2>&1");
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("--face: must be largest, left, right or X,Y (pixels), not 'middle'"), std::string::npos)
      << bad.out;
}

// The same two portraits upside down (a half turn): probe finds both, Biden's
// now on the left, each rolled 180 degrees; a centre it gives picks that face
// for track (found in the turned frame, where the pick chooses as the frame
// shows the faces); --all-faces follows both.
TEST(Cli, ProbeAndTrackFindUpsideDownFacesWhereTheFrameShowsThem) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(obama, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(biden, "portrait_biden.jpg");
  int left_width = 0;
  cv::Mat both = two_portraits(obama, biden, left_width);
  ASSERT_FALSE(both.empty());
  cv::rotate(both, both, cv::ROTATE_180);
  const int obama_from = both.cols - left_width;  // Obama's portrait now lies right of this
  TempDir dir;
  const auto image = dir.path() / "upside_down.png";
  facecap::write_image(image.string(), both);
  const nlohmann::json boxes = probed_face_boxes(image);
  ASSERT_EQ(boxes.size(), 2u) << boxes;
  EXPECT_LT(boxes[0]["centre"][0].get<int>(), obama_from);
  EXPECT_GT(boxes[1]["centre"][0].get<int>(), obama_from);
  for (const auto& box : boxes) EXPECT_EQ(box["roll_degrees"].get<int>(), 180) << boxes;
  for (int i : {0, 1}) {
    const std::string at = face_point(boxes[i]);
    const fs::path out = dir.path() / ("face" + std::to_string(i));
    const RunResult t = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                          out.string() + " --face " + at + " 2>&1 >/dev/null");
    ASSERT_EQ(t.code, 0) << t.out;
    const Vec2f nose = first_landmark(out, 30);
    if (i == 0) {
      EXPECT_LT(nose.x(), obama_from) << "Biden's face, at " << at;
    } else {
      EXPECT_GT(nose.x(), obama_from) << "Obama's face, at " << at;
    }
    // Upside down: the nose tip lies above the eyes' centre in the frame.
    EXPECT_LT(nose.y(), first_landmark(out, 39).y()) << at;
  }
  // --all-faces: both, left to right as the frame shows them.
  const RunResult all = test::run_command(std::string(FACECAP_BINARY) + " track " + image.string() + " -o " +
                                          (dir.path() / "all").string() + " --all-faces 2>&1 >/dev/null");
  ASSERT_EQ(all.code, 0) << all.out;
  EXPECT_LT(first_landmark(dir.path() / "all" / "face_0", 30).x(), obama_from);
  EXPECT_GT(first_landmark(dir.path() / "all" / "face_1", 30).x(), obama_from);
}

// --stream: each frame's row on stdout as it is done (not smoothed unless
// asked), the same as frames.jsonl's, and nothing else there (the closing list of files goes to stderr). A reader
// that stops early (`| head -1`) ends the stream, not the capture.
TEST(Cli, TrackStreamsEachFramesRowOnStdout) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  auto lines_of = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  };
  auto file_lines = [&](const fs::path& p) {
    std::ifstream in(p);
    return lines_of(std::string(std::istreambuf_iterator<char>(in), {}));
  };
  const std::string track =
      std::string(FACECAP_BINARY) + " -q track " + video.string() + " --stream --max-frames 36 -o ";
  const RunResult r = test::run_command(track + (dir.path() / "a").string() + " 2>/dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::vector<std::string> rows = lines_of(r.out);
  EXPECT_EQ(rows.size(), 36u);
  EXPECT_EQ(rows, file_lines(dir.path() / "a" / "frames.jsonl"));
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(nlohmann::json::parse(rows[i])["frame"], int(i));
  // A stream is not held back for smoothing (--smooth-frames): its rows are
  // a run's without it, not the default's.
  const std::string plain = std::string(FACECAP_BINARY) + " -q track " + video.string() + " --max-frames 36 -o ";
  ASSERT_EQ(test::run_command(plain + (dir.path() / "forward").string() + " --smooth-frames 0 >/dev/null").code, 0);
  EXPECT_EQ(rows, file_lines(dir.path() / "forward" / "frames.jsonl"));
  ASSERT_EQ(test::run_command(plain + (dir.path() / "smoothed").string() + " >/dev/null").code, 0);
  EXPECT_NE(rows, file_lines(dir.path() / "smoothed" / "frames.jsonl"));

  const RunResult early = test::run_command("sh -c '" + track + (dir.path() / "b").string() + " 2>" +
                                            (dir.path() / "b.err").string() + " | head -1'");
  EXPECT_EQ(early.code, 0);
  EXPECT_EQ(lines_of(early.out).size(), 1u);
  EXPECT_EQ(file_lines(dir.path() / "b" / "frames.jsonl").size(), 36u);  // the capture went on
  const std::vector<std::string> err = file_lines(dir.path() / "b.err");
  EXPECT_NE(
      std::find(err.begin(), err.end(), "facecap: stdout was closed; --stream stops, and the files are still written"),
      err.end());
}

// --landmarks-csv and --action-units: the tables are written and named with
// the other files, a row a frame as wide as its header (landmark_table.hpp,
// action_unit_table.hpp).
TEST(Cli, TrackWritesTheLandmarkAndActionUnitTablesAndNamesThem) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const RunResult r =
      run("track " + video.string() + " --landmarks-csv --action-units --max-frames 4 -o " + dir.path().string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const auto& [name, fields] : {std::pair<const char*, size_t>{"landmarks.csv", 3u + 7u * 68u},
                                     std::pair<const char*, size_t>{"action_units.csv", 3u + 2u * 19u}}) {
    const fs::path table = dir.path() / name;
    EXPECT_NE(r.out.find(table.string()), std::string::npos) << r.out;
    const std::vector<std::string> rows = test::read_lines(table);
    ASSERT_EQ(rows.size(), 5u) << name;
    for (const std::string& row : rows) EXPECT_EQ(split_csv_line(row).size(), fields) << row.substr(0, 40);
  }
}

// --refine --detail-maps on real footage: a map for every frame, named with
// the other files, each a 16-bit map of the refinement's detail that
// follows the face (the maps of two frames differ), within detail.json's
// range and its reported extremes.
TEST(Cli, TrackWritesADetailMapForEachRefinedFrame) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  TempDir dir;
  constexpr int kFrames = 36;
  const RunResult r = run("track " + video.string() + " --refine --detail-maps --detail-map-size 512 --max-frames " +
                          std::to_string(kFrames) + " -o " + dir.path().string());
  ASSERT_EQ(r.code, 0) << r.out;
  const fs::path detail = dir.path() / "detail";
  EXPECT_NE(r.out.find(detail.string()), std::string::npos) << r.out;
  std::ifstream info_in(detail / "detail.json");
  const nlohmann::json info = nlohmann::json::parse(info_in);
  EXPECT_EQ(info["maps"], kFrames);
  EXPECT_EQ(info["size"], nlohmann::json({512, 512}));
  EXPECT_EQ(info["encoding"]["clamped_fraction"], 0.0);
  const double range = info["encoding"]["range_mm"], lowest = info["displacement_mm"]["min"],
               highest = info["displacement_mm"]["max"], rms = info["displacement_mm"]["rms"];
  // Measured on this clip: rms 0.046 mm, extremes -0.62 and 0.68 mm.
  EXPECT_GT(rms, 0.01);
  EXPECT_LT(rms, 0.5);
  const auto decode = [&](double v) { return (v / 65535 - 0.5) * 2 * range; };
  cv::Mat first, last;
  for (int frame : {0, kFrames / 2, kFrames - 1}) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%06d.png", frame);
    const cv::Mat map = read_png16(detail / name);
    ASSERT_EQ(map.type(), CV_16UC1) << name;
    ASSERT_EQ(map.size(), cv::Size(512, 512)) << name;
    double lo = 0, hi = 0;
    cv::minMaxLoc(map, &lo, &hi);
    EXPECT_GE(decode(lo), lowest - 1e-3) << name;
    EXPECT_LE(decode(hi), highest + 1e-3) << name;
    EXPECT_GT(decode(hi) - decode(lo), 0.1) << name;
    (frame == 0 ? first : last) = map;
  }
  cv::Mat change;
  cv::absdiff(first, last, change);
  EXPECT_GT(cv::countNonZero(change > 65535 * 0.01 / (2 * range)), 1000);  // texels 0.01 mm apart or more
}

}  // namespace facecap
