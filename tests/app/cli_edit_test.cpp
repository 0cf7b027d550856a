// facecap transform, swap and synth end to end: bad requests, outputs that
// would replace an input, a source taken from a video, and the marks on a
// photo's edit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_support.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/marked_image.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(Cli, EditsOfAVideoWithNoFaceWriteNothingAndSaySo) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(photo, "portrait_obama.jpg");
  TempDir dir;
  const std::string video = (dir.path() / "grey.mp4").string();
  ASSERT_EQ(std::system(
                ("ffmpeg -loglevel error -y -f lavfi -i color=gray:s=160x120:d=0.4 -pix_fmt yuv420p " + video).c_str()),
            0);
  const std::string out = (dir.path() / "out.mp4").string();
  for (const std::string& args : {"transform " + video + " --to happiness -o " + out,
                                  "swap --source " + photo.string() + " --target " + video + " -o " + out}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find("no face found in any frame of " + video), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
    EXPECT_FALSE(std::filesystem::exists(out + ".json")) << args;
  }
}

TEST(Cli, TransformRejectsBadRequestsWithOneLine) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const std::string out = (dir.path() / "out.mp4").string();
  for (const std::string& args :
       {"transform " + video.string() + " --to fear --models " + (dir.path() / "none").string() + " -o " + out,
        "transform " + video.string() + " --schedule " + (dir.path() / "none.txt").string() + " -o " + out,
        "transform " + video.string() + " --to happiness --gltf /proc/facecap-test/a.glb -o " + out,
        "transform " + (dir.path() / "missing.mp4").string() + " --to happiness -o " + out,
        "transform " + video.string() + " --all-faces --face-schedule 1=" + (dir.path() / "none.txt").string() +
            " -o " + out,
        "transform " + video.string() + " --to happiness --matte " + out + " -o " + out,
        "transform " + video.string() + " --to happiness --matte /proc/facecap-test/m.mp4 -o " + out}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

// The expression may be named by its adjective, in any case; an unknown one
// is refused with the choices, before any work.
TEST(Cli, TransformTakesAnAdjectiveAndNamesTheChoicesOtherwise) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const std::string out = (dir.path() / "out.mp4").string();
  const RunResult bad = run("transform " + video.string() + " --to contempt -o " + out);
  EXPECT_EQ(bad.code, 2);  // a usage error, before any work
  EXPECT_NE(bad.out.find("--to: must be one of"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("happy"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("not 'contempt'"), std::string::npos) << bad.out;
  EXPECT_FALSE(std::filesystem::exists(out));
  // So does every command that takes an expression, before any work.
  const std::pair<std::string, std::string> others[] = {
      {"transform " + video.string() + " --from glee --to anger -o " + out, "--from: must be one of"},
      {"eval transform --video " + video.string() + " --to contempt", "--to: must be one of"},
      {"bench transform " + video.string() + " --to contempt", "--to: must be one of"}};
  for (const auto& [args, message] : others) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_EQ(r.out.rfind(message, 0), 0u) << r.out;
  }
  const RunResult good = run("transform " + video.string() + " --to Happy --max-frames 8 --lip-weight 30 -o " + out);
  ASSERT_EQ(good.code, 0) << good.out;
  std::ifstream sidecar(out + ".json");
  const std::string text((std::istreambuf_iterator<char>(sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("neutral to happiness"), std::string::npos) << text;
  EXPECT_NE(text.find("\"lip_weight\": \"30\""), std::string::npos) << text;  // the edit's parameters
}

// An output path that is a folder is refused up front, by name, for the
// video and for the glTF of both edits; the folder is left alone.
TEST(Cli, EditsRefuseAFolderAsTheirOutput) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(portrait, "portrait_biden.jpg");
  TempDir dir;
  const std::string folder = dir.path().string(), out = (dir.path() / "out.mp4").string();
  const std::string swap = "swap --source " + portrait.string() + " --target " + video.string();
  const std::string transform = "transform " + video.string() + " --to happiness";
  for (const std::string& args : {swap + " -o " + folder, swap + " -o " + out + " --gltf " + folder,
                                  transform + " -o " + folder, transform + " -o " + out + " --gltf " + folder}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find("is a folder"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

// An output that names an input (the same spelling, another one, or a link
// to it) is refused up front: committing it would replace the footage the
// edit was made from. The input is left as it was.
TEST(Cli, OutputsNeverReplaceTheirInput) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(portrait, "portrait_biden.jpg");
  TempDir dir;
  const fs::path clip = dir.path() / "clip.mp4", photo = dir.path() / "photo.jpg", link = dir.path() / "link.mp4";
  fs::copy_file(video, clip);
  fs::copy_file(portrait, photo);
  fs::create_symlink(clip, link);
  const auto clip_size = fs::file_size(clip), photo_size = fs::file_size(photo);
  const std::string c = clip.string(), p = photo.string(), out = (dir.path() / "out.mp4").string();
  const std::string swap = "swap --source " + p + " --target " + c + " --max-frames 3";
  const std::string transform = "transform " + c + " --max-frames 3";
  const std::string spelled_again = (dir.path() / "." / "clip.mp4").string();
  for (const std::string& args :
       {transform + " -o " + c, transform + " -o " + spelled_again, transform + " -o " + link.string(),
        transform + " -o " + out + " --gltf " + c, transform + " -o " + out + " --plot " + c, swap + " -o " + c,
        swap + " -o " + p, swap + " -o " + out + " --gltf " + p}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find("the input would be replaced"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  // Nor does track write its overlay over an overlay it is given.
  const fs::path overlay = dir.path() / "overlay.mp4";
  fs::copy_file(video, overlay);
  const RunResult r = run("track " + overlay.string() + " -o " + dir.path().string() + " --overlay --max-frames 3");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("the input would be replaced"), std::string::npos) << r.out;
  EXPECT_EQ(fs::file_size(overlay), clip_size);
  EXPECT_EQ(fs::file_size(clip), clip_size);
  EXPECT_EQ(fs::file_size(photo), photo_size);
}

TEST(Cli, SwapRejectsAPhotoWithoutAFaceWithOneLine) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  std::ofstream(dir.path() / "text.jpg") << "not an image";
  const std::string out = (dir.path() / "out.mp4").string();
  // A corrupt image, a missing file, and a folder with no photos in it.
  std::filesystem::create_directories(dir.path() / "empty");
  for (const std::string& photo :
       {(dir.path() / "text.jpg").string(), (dir.path() / "missing.jpg").string(), (dir.path() / "empty").string()}) {
    const RunResult r = run("swap --source " + photo + " --target " + video.string() + " -o " + out);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find(photo), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  EXPECT_NE(run("swap --target " + video.string() + " -o " + out).code, 0);  // --source is required
  FACECAP_REQUIRE_DATA(portrait, "portrait_biden.jpg");
  // A glTF path that cannot be written fails before the work, naming it.
  const RunResult no_gltf = run("swap --source " + portrait.string() + " --target " + video.string() + " -o " + out +
                                " --gltf /proc/facecap-test/a.glb");
  EXPECT_EQ(no_gltf.code, 1) << no_gltf.out;
  EXPECT_EQ(lines(no_gltf.out), 1) << no_gltf.out;
  EXPECT_NE(no_gltf.out.find("/proc/facecap-test"), std::string::npos) << no_gltf.out;
  EXPECT_FALSE(std::filesystem::exists(out));
  // So do a face's own source that is missing, and a matte that cannot be
  // written or that is the output.
  for (const std::string& extra : {" --all-faces --face-source 1=" + (dir.path() / "missing.jpg").string(),
                                   std::string(" --matte /proc/facecap-test/m.mp4"), " --matte " + out}) {
    const RunResult bad =
        run("swap --source " + portrait.string() + " --target " + video.string() + " -o " + out + extra);
    EXPECT_EQ(bad.code, 1) << extra << ": " << bad.out;
    EXPECT_EQ(lines(bad.out), 1) << bad.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << extra;
  }
  // A gain on the photo's detail outside [0, 1], or a residual shading
  // width outside [0, 100] mm, is refused by name before any work.
  for (const auto& [flag, value] : std::vector<std::pair<std::string, std::string>>{{"--photo-detail", "2"},
                                                                                    {"--photo-detail", "-0.5"},
                                                                                    {"--photo-detail", "lots"},
                                                                                    {"--residual-shading", "-5"},
                                                                                    {"--residual-shading", "500"},
                                                                                    {"--residual-shading", "wide"}}) {
    const RunResult bad = run("swap --source " + portrait.string() + " --target " + video.string() + " -o " + out +
                              " " + flag + " " + value);
    EXPECT_NE(bad.code, 0) << bad.out;
    EXPECT_NE(bad.out.find(flag), std::string::npos) << bad.out;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(Cli, SwapTakesItsSourceFromAVideo) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(source, "talking_webcam2_400x300.mp4");
  FACECAP_REQUIRE_DATA(target, "talking_webcam_400x300.mp4");
  TempDir dir;
  const std::string out = (dir.path() / "out.mp4").string();
  const RunResult r = run("swap --source " + source.string() + " --source-frames 8 --target " + target.string() +
                          " --max-frames 4 -o " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(std::filesystem::exists(out));
  std::ifstream sidecar(out + ".json");
  const std::string mark((std::istreambuf_iterator<char>(sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(mark.find("\"source_frames_used\": \"8\""), std::string::npos) << mark;
  EXPECT_NE(mark.find("\"expression_ratio\": \"true\""), std::string::npos) << mark;  // the default
  const RunResult bad =
      run("swap --source " + source.string() + " --source-frames 0 --target " + target.string() + " -o " + out);
  EXPECT_EQ(bad.code, 2) << bad.out;  // a usage error, before any work
  EXPECT_NE(bad.out.find("--source-frames"), std::string::npos) << bad.out;
  EXPECT_TRUE(std::filesystem::exists(out));  // the good output of the first run is kept

  // A folder of photos of the face taken apart (here a frame and its mirror
  // image: to the shot-cut test, as unlike as two rooms) is one face: its
  // identity is solved over both, not over the first alone.
  const fs::path photos = dir.path() / "photos";
  fs::create_directories(photos);
  const RunResult extracted = test::run_command("ffmpeg -nostdin -v error -y -i " + source.string() + " -frames:v 1 " +
                                                (photos / "1.png").string() + " 2>&1");
  ASSERT_EQ(extracted.code, 0) << extracted.out;
  const cv::Mat photo = facecap::read_image((photos / "1.png").string());
  cv::Mat mirrored;
  cv::flip(photo, mirrored, 1);
  facecap::write_image((photos / "2.png").string(), mirrored);
  const RunResult folder =
      run("swap --source " + photos.string() + " --target " + target.string() + " --max-frames 2 -o " + out);
  ASSERT_EQ(folder.code, 0) << folder.out;
  std::ifstream folder_sidecar(out + ".json");
  const std::string folder_mark((std::istreambuf_iterator<char>(folder_sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(folder_mark.find("\"source_frames_used\": \"2\""), std::string::npos) << folder_mark;
  const std::string plain = (dir.path() / "plain.mp4").string();
  ASSERT_EQ(run("swap --source " + source.string() + " --source-frames 8 --target " + target.string() +
                " --max-frames 4 --no-expression-ratio -o " + plain)
                .code,
            0);
  std::ifstream plain_sidecar(plain + ".json");
  const std::string plain_mark((std::istreambuf_iterator<char>(plain_sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(plain_mark.find("\"expression_ratio\": \"false\""), std::string::npos) << plain_mark;
}

// A photo's edit can be a photo (.png, .jpg): the marks are in the file's own
// metadata (XMP with IPTC's DigitalSourceType, text chunks or a comment) as
// well as in its sidecar; the picture outside the face is the input's.
TEST(Cli, EditsOfAPhotoWriteAMarkedPhoto) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(source, "portrait_biden.jpg");
  FACECAP_REQUIRE_DATA(target, "portrait_obama.jpg");
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const cv::Mat input = facecap::read_image(target.string());
  ASSERT_FALSE(input.empty());
  const cv::Rect corner(0, 0, 120, 120);  // curtain and flag, far from the face
  auto face_change = [&](const cv::Mat& out) {
    const cv::Rect face(input.cols / 3, input.rows / 12, input.cols / 3, input.rows / 4);
    return cv::norm(out(face), input(face), cv::NORM_L1) / face.area();
  };

  const fs::path swapped = dir.path() / "swapped.jpg";
  const RunResult s =
      run("swap --source " + source.string() + " --target " + target.string() + " -o " + swapped.string());
  ASSERT_EQ(s.code, 0) << s.out;
  EXPECT_TRUE(carries_synthetic_marks(swapped));
  const auto swap_tags = read_image_tags(swapped);
  EXPECT_EQ(swap_tags.at("facecap_edit"), "face-swap");
  EXPECT_NE(swap_tags.at("comment").find("The face in this image was replaced"), std::string::npos);
  const cv::Mat swap_out = facecap::read_image(swapped.string());
  ASSERT_EQ(swap_out.size(), input.size());
  EXPECT_GT(face_change(swap_out), 10.0);                                                  // another face
  EXPECT_LT(cv::norm(swap_out(corner), input(corner), cv::NORM_L1) / corner.area(), 3.0);  // JPEG's own

  const fs::path smiling = dir.path() / "smiling.png";
  const RunResult t = run("transform " + target.string() + " --to happiness -o " + smiling.string());
  ASSERT_EQ(t.code, 0) << t.out;
  EXPECT_TRUE(carries_synthetic_marks(smiling));
  EXPECT_EQ(read_image_tags(smiling).at("facecap_edit"), "expression-transform");
  const cv::Mat smile_out = facecap::read_image(smiling.string());
  ASSERT_EQ(smile_out.size(), input.size());
  EXPECT_GT(face_change(smile_out), 5.0);
  EXPECT_EQ(cv::norm(smile_out(corner), input(corner), cv::NORM_INF), 0.0);  // PNG: exactly the input

  // A video's edit is a video: an image name for it is refused before any work.
  const fs::path still = dir.path() / "still.png";
  const RunResult v = run("transform " + video.string() + " --to happiness -o " + still.string());
  EXPECT_EQ(v.code, 1);
  EXPECT_EQ(lines(v.out), 1) << v.out;
  EXPECT_NE(v.out.find("an image output (.png, .jpg, .jpeg) is for a photo input"), std::string::npos) << v.out;
  EXPECT_FALSE(fs::exists(still));
}

// A synthetic render given a real portrait's skin says so in its marks, and
// a portrait that cannot be used is one line, before anything is written.
TEST(Cli, SynthWithAPortraitsSkinSaysSoInItsMarks) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(portrait, "portrait_obama.jpg");
  TempDir dir;
  const fs::path out = dir.path() / "render";
  const RunResult r = run("synth -o " + out.string() + " --frames 2 --size 320x240 --face-photo " + portrait.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(carries_synthetic_marks(out / "video.mp4"));
  const nlohmann::json mark = nlohmann::json::parse(test::read_file(sidecar_path(out / "video.mp4")));
  EXPECT_EQ(mark.at("parameters").at("face_texture"), "portrait_obama.jpg");
  EXPECT_EQ(mark.at("sources"), nlohmann::json::array({portrait.string()}));
  EXPECT_NE(mark.at("description").get<std::string>().find("a real person"), std::string::npos);
  // The painted skin says no real person is shown.
  const fs::path painted = dir.path() / "painted";
  ASSERT_EQ(run("synth -o " + painted.string() + " --frames 1 --size 320x240").code, 0);
  const nlohmann::json painted_mark = nlohmann::json::parse(test::read_file(sidecar_path(painted / "video.mp4")));
  EXPECT_FALSE(painted_mark.at("parameters").contains("face_texture"));
  EXPECT_NE(painted_mark.at("description").get<std::string>().find("no real person"), std::string::npos);

  const fs::path missing = dir.path() / "missing.jpg", none = dir.path() / "none";
  const RunResult bad = run("synth -o " + none.string() + " --frames 2 --face-photo " + missing.string());
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_EQ(lines(bad.out), 1) << bad.out;
  EXPECT_NE(bad.out.find(missing.string()), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(none));
  // Real footage has a skin of its own.
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  for (const std::string& eval : {"eval track --video " + video.string(), "eval refine --video " + video.string(),
                                  "eval landmarks " + portrait.string() + " none.pts"}) {
    const RunResult refused = run(eval + " --face-photo " + portrait.string());
    EXPECT_EQ(refused.code, 2) << eval << ": " << refused.out;
    EXPECT_EQ(lines(refused.out), 2) << refused.out;  // the error, and CLI11's pointer to --help
    EXPECT_NE(refused.out.find("--face-photo: needs --synthetic"), std::string::npos) << refused.out;
  }
}

}  // namespace facecap
