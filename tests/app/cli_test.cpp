// The facecap program end to end: exit codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "app/command.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/marked_image.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/refine/compute_device.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

using RunResult = test::CommandResult;

RunResult run(const std::string& args) {
  return test::run_command(std::string(FACECAP_BINARY) + " -q " + args + " 2>&1");
}

int lines(const std::string& s) { return test::count_lines(s); }

// The JSON object a command prints; where it fails, an exception carrying its
// exit code and output, which fails the test there.
nlohmann::json json_from(const std::string& args) {
  const RunResult r = run(args);
  if (r.code != 0) throw std::runtime_error(args + " exited with " + std::to_string(r.code) + ": " + r.out);
  return nlohmann::json::parse(r.out);
}

}  // namespace

TEST(Cli, HelpListsTheSubcommands) {
  const RunResult r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* sub : {"probe", "model", "synth", "eval", "demo", "track", "transform", "swap", "bench"}) {
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
  }
}

TEST(Cli, BadInputsExitNonZeroWithOneLine) {
  TempDir dir;
  std::ofstream(dir.path() / "empty.mp4").close();
  std::ofstream(dir.path() / "text.mp4") << "not a video";
  for (const std::string& input : {(dir.path() / "missing.mp4").string(), (dir.path() / "empty.mp4").string(),
                                   (dir.path() / "text.mp4").string(), dir.path().string()}) {
    const RunResult r = run("probe " + input);
    EXPECT_EQ(r.code, 1) << input << ": " << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_EQ(r.out.rfind("facecap: error: ", 0), 0u) << r.out;
  }
}

// A camera that is not there (this machine has none at cam:7) is one line,
// without OpenCV's warnings from the backends it tried.
TEST(Cli, AMissingCameraIsOneLine) {
  const RunResult r = run("probe cam:7");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("cannot open camera 7"), std::string::npos) << r.out;
}

TEST(Cli, UnwritableOutputFolderIsAClearError) {
  FACECAP_REQUIRE_MODEL(model);
  const RunResult r = run("synth -o /proc/facecap-test --frames 2");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/proc/facecap-test"), std::string::npos) << r.out;
}

TEST(Cli, BadOptionValuesAreNamed) {
  FACECAP_REQUIRE_MODEL(model);
  const RunResult r = run("synth -o /tmp/x --frames 0");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--frames"), std::string::npos) << r.out;
  EXPECT_NE(run("synth -o /tmp/x --size huge").out.find("--size"), std::string::npos);
  // Usage errors exit with 2, whichever CLI11 error they are: a missing
  // argument, a value out of range, an unknown option or subcommand.
  for (const char* args : {"probe",
                           "track in.mp4 -o x --start -5",
                           "track in.mp4 -o x --bogus",
                           "nosuchcommand",
                           "transform in.mp4 -o x.mp4 --face 3",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 "
                           "--source-face up",
                           "track in.mp4 -o x --all-faces --max-faces 0",
                           "track in.mp4 -o x --max-faces 3",
                           "track in.mp4 -o x --all-faces --search-every 0",
                           "track in.mp4 -o x --all-faces --face left",
                           "track in.mp4 -o x --all-faces --stream",
                           "bench track in.mp4 --all-faces --refine",
                           "transform in.mp4 -o x.mp4 --all-faces --face left",
                           "transform in.mp4 -o x.mp4 --all-faces --plot p.png",
                           "transform in.mp4 -o x.mp4 --all-faces --gltf x.glb",
                           "transform in.mp4 -o x.mp4 --max-faces 2",
                           "track in.mp4 -o x --livelink-udp host:0",
                           "track in.mp4 -o x --livelink-udp :11111",
                           "track in.mp4 -o x --livelink-subject me",
                           "track in.mp4 -o x --texture --texture-frames 0",
                           "track in.mp4 -o x --texture-frames 5",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 --all-faces --face left",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 --all-faces --gltf x.glb",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 --leave-faces 0",
                           "transform in.mp4 -o x.mp4 --leave-faces 1",
                           "transform in.mp4 -o x.mp4 --all-faces --leave-faces -1",
                           "transform in.mp4 -o x.mp4 --all-faces --leave-faces a",
                           "transform in.mp4 -o x.mp4 --face-to 1=sadness",
                           "transform in.mp4 -o x.mp4 --all-faces --face-to sadness",
                           "transform in.mp4 -o x.mp4 --all-faces --face-to 1=glee",
                           "transform in.mp4 -o x.mp4 --all-faces --face-to -1=anger",
                           "transform in.mp4 -o x.mp4 --all-faces --face-schedule 1=",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 --face-source 1=c.jpg",
                           "swap --source a.jpg --target b.mp4 -o x.mp4 --all-faces --face-source c.jpg"})
    EXPECT_EQ(run(args).code, 2) << args;
  const RunResult face = run("swap --source a.jpg --target b.mp4 -o x.mp4 --source-face up");
  EXPECT_EQ(lines(face.out), 2) << face.out;  // the error, and CLI11's pointer to --help
  EXPECT_NE(face.out.find("--source-face: must be largest, left, right or X,Y (pixels), not 'up'"), std::string::npos)
      << face.out;
  const RunResult shading = run("eval refine --video whatever.mp4 --true-shading");
  EXPECT_EQ(shading.code, 1) << shading.out;
  EXPECT_EQ(lines(shading.out), 1) << shading.out;
  EXPECT_NE(shading.out.find("--true-shading"), std::string::npos) << shading.out;
}

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
  r = run("track " + video.string() + " -o " + dir.path().string() + " --init-frames 0");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("--init-frames"), std::string::npos) << r.out;
  r = run("track " + video.string() + " -o " + dir.path().string() + " --smooth-frames -1");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("--smooth-frames"), std::string::npos) << r.out;
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

TEST(Cli, TrackOfAnImageWithNoFaceIsAnErrorThatSaysSo) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const auto image = dir.path() / "grey.ppm";
  {
    std::ofstream f(image, std::ios::binary);
    f << "P6 320 240 255\n" << std::string(320 * 240 * 3, char(128));
  }
  std::filesystem::create_directories(dir.path() / "out");
  std::ofstream(dir.path() / "out" / "identity.json") << "{}";    // an earlier run's
  std::ofstream(dir.path() / "out" / "animation.glb") << "glTF";  // an earlier run's
  const RunResult r = run("track " + image.string() + " -o " + (dir.path() / "out").string() + " --gltf");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("no face found in " + image.string()), std::string::npos) << r.out;
  // The per-frame record is complete: one frame, lost.
  std::ifstream csv(dir.path() / "out" / "frames.csv");
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row));
  EXPECT_EQ(row.rfind("0,0,lost,", 0), 0u) << row;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "identity.json"));  // no identity was seen here
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "animation.glb"));  // nor a face to animate
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
       {"transform " + video.string() + " --to contempt -o " + out,
        "transform " + video.string() + " --to anger --intensity 2 -o " + out,
        "transform " + video.string() + " --to fear --models " + (dir.path() / "none").string() + " -o " + out,
        "transform " + video.string() + " --schedule " + (dir.path() / "none.txt").string() + " -o " + out,
        "transform " + video.string() + " --to happiness --init-frames 0 -o " + out,
        "transform " + video.string() + " --to happiness --smooth-frames -1 -o " + out,
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
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.out.find("--to must be one of"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("happy"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("not 'contempt'"), std::string::npos) << bad.out;
  const RunResult good = run("transform " + video.string() + " --to Happy --max-frames 8 -o " + out);
  ASSERT_EQ(good.code, 0) << good.out;
  std::ifstream sidecar(out + ".json");
  const std::string text((std::istreambuf_iterator<char>(sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("neutral to happiness"), std::string::npos) << text;
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
  for (const auto& [option, value] : {std::pair{"--init-frames", " 0"}, std::pair{"--smooth-frames", " -1"}}) {
    const RunResult r =
        run("swap --source " + portrait.string() + " --target " + video.string() + " -o " + out + " " + option + value);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1) << r.out;
    EXPECT_NE(r.out.find(option), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
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
  EXPECT_EQ(bad.code, 1) << bad.out;
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
    EXPECT_EQ(refused.code, 1) << eval << ": " << refused.out;
    EXPECT_EQ(lines(refused.out), 1) << refused.out;
    EXPECT_NE(refused.out.find("--face-photo needs --synthetic"), std::string::npos) << refused.out;
  }
}

// eval track --photos fits each K-th synthetic frame alone and reports the
// photos' identity errors as JSON; it has no meaning for real footage or
// dlib's landmarks, which are refused in one line.
TEST(Cli, EvalTrackFitsSyntheticFramesAsPhotos) {
  FACECAP_REQUIRE_MODEL(model);
  const nlohmann::json j = json_from("eval track --synthetic 6 --photos 3 --size 640x480");
  EXPECT_EQ(j.at("photos"), 2) << j.dump();
  EXPECT_GT(j.at("shape_error_mm").get<double>(), 0.0);
  EXPECT_LT(j.at("shape_error_mm").get<double>(), 5.0);
  for (const std::string& bad : {std::string("eval track --synthetic 6 --photos 3 --landmarks dlib"),
                                 std::string("eval track --video none.mp4 --photos 3")}) {
    const RunResult refused = run(bad);
    EXPECT_EQ(refused.code, 1) << bad << ": " << refused.out;
    EXPECT_EQ(lines(refused.out), 1) << refused.out;
    EXPECT_NE(refused.out.find("--photos"), std::string::npos) << refused.out;
  }
}

// eval landmarks FOLDER: one JSON object with both sets' summaries and a row
// per annotated image; a folder without annotations is a one-line error.
TEST(Cli, EvalLandmarksScoresAFolderOfAnnotatedImages) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(lfpw, "lfpw_image_0010.png");
  FACECAP_REQUIRE_DATA(lfpw_pts, "lfpw_image_0010.pts");
  TempDir dir;
  fs::copy_file(lfpw, dir.path() / "face.png");
  fs::copy_file(lfpw_pts, dir.path() / "face.pts");
  const nlohmann::json j = json_from("eval landmarks " + dir.path().string());
  EXPECT_EQ(j["dlib"]["images"], 1);
  EXPECT_EQ(j["fitted"]["scored"], 1);
  EXPECT_GT(double(j["fitted"]["auc_0.08"]), 0.4);  // 0.60 measured: NME 0.032
  EXPECT_EQ(j["fitted"]["failure_rate_0.08"], 0.0);
  ASSERT_EQ(j["per_image"].size(), 1u);
  EXPECT_EQ(j["per_image"][0]["image"], "face.png");
  fs::remove(dir.path() / "face.pts");
  const RunResult bare = run("eval landmarks " + dir.path().string());
  EXPECT_EQ(bare.code, 1) << bare.out;
  EXPECT_EQ(lines(bare.out), 1) << bare.out;
  EXPECT_NE(bare.out.find("annotation"), std::string::npos) << bare.out;
}

TEST(Cli, ProbeDescribesAVideoAsJson) {
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  const RunResult r = run("probe " + video.string());
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("\"width\": 1280"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"audio\": true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 1"), std::string::npos) << r.out;
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
// macroblock ("[h264 @ ...] error while decoding MB") stays out of the output.
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
  EXPECT_LE(lines(r.out), 3) << r.out;
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

// --landmarks-csv: the table is written and named with the other files, a
// row a frame as wide as its header (landmark_table.hpp).
TEST(Cli, TrackWritesTheLandmarkTableAndNamesIt) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const RunResult r = run("track " + video.string() + " --landmarks-csv --max-frames 4 -o " + dir.path().string());
  ASSERT_EQ(r.code, 0) << r.out;
  const fs::path table = dir.path() / "landmarks.csv";
  EXPECT_NE(r.out.find(table.string()), std::string::npos) << r.out;
  const std::vector<std::string> rows = test::read_lines(table);
  ASSERT_EQ(rows.size(), 5u);
  for (const std::string& row : rows) EXPECT_EQ(split_csv_line(row).size(), 3u + 7u * 68u) << row.substr(0, 40);
}

// The README's main job, end to end on a short performance: it prints its
// report as JSON, loses no frame, recovers the head's turn to a few degrees
// (dlib's landmarks on the renders: 3.1 deg median on 60 frames), and keeps
// its input and outputs where asked.
TEST(Cli, DemoCapturesTheSyntheticPerformanceAndReportsAgainstItsTruth) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const auto kept = dir.path() / "kept";
  const RunResult r =
      test::run_command(std::string(FACECAP_BINARY) + " -q demo --frames 20 --keep " + kept.string() + " 2>/dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["capture"]["frames"], 20);
  EXPECT_EQ(report["capture"]["lost_frames"], 0);
  EXPECT_LT(report["recovered_vs_truth"]["rotation_error_deg_median"].get<double>(), 6.0) << r.out;
  EXPECT_TRUE(std::filesystem::exists(report["input"]["video"].get<std::string>())) << r.out;
  EXPECT_TRUE(
      std::filesystem::exists(std::filesystem::path(report["capture"]["outputs"].get<std::string>()) / "frames.csv"))
      << r.out;
}

// --device names what it takes, and asking for CUDA where there is none is a
// one-line error, not a crash or a silent fall back to the CPU.
TEST(Cli, DeviceOptionNamesWhatItNeeds) {
  RunResult r = run("eval refine --synthetic 1 --device gpu");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("--device"), std::string::npos) << r.out;
  if (cuda_device_available()) GTEST_SKIP() << "a CUDA device is present";
  r = run("eval refine --synthetic 1 --device cuda");
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("cuda"), std::string::npos) << r.out;
}

// bench track --refine reports each part of a frame's refinement, and the
// parts add up: each level's solve within its pass, the samplings within the
// frame, the first frame (the hierarchy's build) within the whole.
TEST(Cli, BenchTrackWithRefinementReportsEachPart) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const nlohmann::json j = json_from("bench track " + video.string() + " --refine --device cpu --max-frames 40");
  const nlohmann::json& refine = j.at("refine");
  const int frames = refine.at("frames").get<int>();
  ASSERT_EQ(frames, 40) << j.dump();
  EXPECT_EQ(refine.at("device"), "cpu");
  const auto& pass = refine.at("displacement_ms_per_level");
  const auto& solve = refine.at("displacement_solve_ms_per_level");
  ASSERT_GE(pass.size(), 1u);
  ASSERT_EQ(pass.size(), solve.size());
  double levels = 0;
  for (size_t l = 0; l < pass.size(); ++l) {
    EXPECT_GT(solve[l].get<double>(), 0.0) << "level " << l;
    EXPECT_LT(solve[l].get<double>(), pass[l].get<double>()) << "level " << l;
    levels += pass[l].get<double>();
  }
  const double total = refine.at("total_ms_per_frame").get<double>();
  const double sampling = refine.at("sampling_ms_per_frame").get<double>();
  EXPECT_GT(sampling, 0.0);
  EXPECT_LT(sampling, refine.at("lighting_ms_per_frame").get<double>() + levels);
  EXPECT_LT(levels, total);
  // The albedo is fixed after the first 30 frames; the frames after it cost less.
  const double steady = refine.at("total_ms_per_frame_albedo_fixed").get<double>();
  EXPECT_GT(steady, 0.0);
  EXPECT_LT(steady, total);
  const nlohmann::json& stage = j.at("refine_stage");
  EXPECT_EQ(stage.at("frames").get<int>(), frames);
  EXPECT_GT(stage.at("first_refine_ms").get<double>(), 0.0);
  EXPECT_LT(stage.at("first_refine_ms").get<double>(), total * frames);
  EXPECT_GT(stage.at("fps_after_startup").get<double>(), 0.0);
}

// Real footage's displacement problems saved, then solved again on their
// own: what a GPU machine runs to compare the devices without the model.
TEST(Cli, SavedDisplacementProblemsSolveAgainOnTheirOwn) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const auto problems = dir.path() / "problems";
  RunResult r = run("eval refine --video " + video.string() + " --max-frames 3 --device cpu --save-problems " +
                    problems.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(std::filesystem::exists(problems / "frame0002_level0.fcdp"));
  const nlohmann::json j = json_from("bench displacement " + problems.string() + " --device cpu --repeats 1");
  EXPECT_EQ(j.at("frames").get<int>(), 3);
  ASSERT_GE(j.at("levels").get<int>(), 1);
  const auto& ms = j.at("cpu").at("ms_per_level");
  ASSERT_EQ(ms.size(), j.at("levels").get<size_t>());
  for (const auto& v : ms) EXPECT_GT(v.get<double>(), 0.0);
  EXPECT_GT(j.at("free_vertices_per_level").at(0).get<int>(), 100);
  // An empty folder, and --check without a second device: one-line errors.
  std::filesystem::create_directories(dir.path() / "empty");
  r = run("bench displacement " + (dir.path() / "empty").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_EQ(lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("no .fcdp"), std::string::npos) << r.out;
  r = run("bench displacement " + problems.string() + " --device cpu --check");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--check"), std::string::npos) << r.out;
}

// The pool's parallel loops and sums (the identity solve's per-frame
// eliminations, the albedo's conjugate gradients, the displacement solve)
// add their parts in fixed blocks and in order, so a capture with its
// refinement comes out byte for byte the same on any number of threads.
TEST(Cli, TrackingAndRefinementDoNotDependOnTheThreadCount) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  TempDir dir;
  std::vector<std::string> outputs;
  for (const int threads : {1, 3}) {
    const fs::path out = dir.path() / ("threads_" + std::to_string(threads));
    const RunResult r =
        test::run_command("FACECAP_THREADS=" + std::to_string(threads) + " " + std::string(FACECAP_BINARY) +
                          " -q track " + video.string() + " -o " + out.string() + " --refine --max-frames 36 2>&1");
    ASSERT_EQ(r.code, 0) << r.out;
    std::string all;
    for (const char* name : {"frames.csv", "identity.json", "albedo.png"}) {
      const std::string bytes = test::read_file(out / name);
      ASSERT_FALSE(bytes.empty()) << name;
      all += bytes;
    }
    outputs.push_back(all);
  }
  EXPECT_TRUE(outputs[0] == outputs[1]) << "the outputs on 1 and 3 threads differ";
}

// bench swap --tracked-first times the swap on a target captured first, and
// says so, with the CPU time of each of its threads; it is one face's, so
// --all-faces with it is a usage error.
TEST(Cli, BenchSwapTrackedFirstTimesTheSwapAloneAndSaysSo) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(target, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(photo, "portrait_biden.jpg");
  const std::string args = "bench swap --source " + photo.string() + " --target " + target.string();
  const nlohmann::json j = json_from(args + " --tracked-first --max-frames 12");
  EXPECT_TRUE(j["swap"]["tracked_first"].get<bool>());
  EXPECT_EQ(j["swap"]["frames"].get<int>(), 12);
  EXPECT_GT(j["swap"]["swap_fps"].get<double>(), 0.0);
  // The CPU budget: each of the swap's threads and the encoder did some work.
  for (const char* part : {"swap_thread", "preparation", "lighting", "encoder"})
    EXPECT_GT(j["swap"]["cpu_ms_per_frame"][part].get<double>(), 0.0) << part;
  EXPECT_GE(j["swap"]["cpu_ms_per_frame"]["pool"].get<double>(), 0.0);
  // facecap's threads all together hold each of the swap's.
  const nlohmann::json& cpu = j["swap"]["cpu_ms_per_frame"];
  const double threads = cpu["swap_thread"].get<double>() + cpu["preparation"].get<double>() +
                         cpu["lighting"].get<double>() + cpu["pool"].get<double>();
  EXPECT_GE(cpu["facecap"].get<double>(), 0.95 * threads);
  const RunResult both = run(args + " --tracked-first --all-faces");
  EXPECT_EQ(both.code, 2) << both.out;
}

// bench transform times the edit and gives the CPU budget of its threads:
// the edit's, the lighting's, the encoder's, and facecap's as a whole,
// which holds the others (and capture's).
TEST(Cli, BenchTransformGivesTheEditsSpeedAndItsCpuBudget) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const nlohmann::json j = json_from("bench transform " + video.string() + " --max-frames 40");
  const nlohmann::json& t = j["transform"];
  EXPECT_EQ(t["frames"].get<int>(), 40);
  EXPECT_GT(t["edit_fps"].get<double>(), 0.0);
  const nlohmann::json& cpu = t["cpu_ms_per_frame"];
  for (const char* part : {"edit_thread", "lighting", "encoder", "facecap"})
    EXPECT_GT(cpu[part].get<double>(), 0.0) << part;
  const double threads = cpu["edit_thread"].get<double>() + cpu["lighting"].get<double>() + cpu["pool"].get<double>();
  EXPECT_GE(cpu["facecap"].get<double>(), 0.95 * threads);
  // Capture (decoding, detection, landmarks, fits) is facecap's too.
  EXPECT_GT(cpu["facecap"].get<double>(), threads);
}

// --crf and --x264-preset reach x264, which writes its settings into the
// stream; values x264 lacks are refused before any work, naming the option.
TEST(Cli, EncodingOptionsReachTheEncoderAndBadOnesAreRefused) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  auto x264_settings = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = bytes.find("options: ");
    return at == std::string::npos ? std::string() : bytes.substr(at, 600);
  };
  const fs::path chosen = dir.path() / "chosen", plain = dir.path() / "plain";
  const std::string track = "track " + video.string() + " --overlay --max-frames 4 -o ";
  ASSERT_EQ(run(track + chosen.string() + " --crf 30 --x264-preset ultrafast").code, 0);
  ASSERT_EQ(run(track + plain.string()).code, 0);
  const std::string settings = x264_settings(chosen / "overlay.mp4"), defaults = x264_settings(plain / "overlay.mp4");
  EXPECT_NE(settings.find("crf=30.0"), std::string::npos) << settings;
  EXPECT_NE(settings.find("cabac=0"), std::string::npos) << settings;  // ultrafast's CAVLC
  EXPECT_NE(defaults.find("crf=18.0"), std::string::npos) << defaults;
  EXPECT_NE(defaults.find("cabac=1"), std::string::npos) << defaults;  // veryfast's CABAC

  const fs::path out = dir.path() / "out.mp4";
  FACECAP_REQUIRE_DATA(portrait, "portrait_biden.jpg");
  const std::string swap = "swap --source " + portrait.string() + " --target " + video.string() + " -o " + out.string();
  const std::string transform = "transform " + video.string() + " -o " + out.string();
  // The edits' outputs take them too.
  ASSERT_EQ(run(swap + " --max-frames 3 --crf 31 --x264-preset superfast").code, 0);
  const std::string swapped = x264_settings(out);
  EXPECT_NE(swapped.find("crf=31.0"), std::string::npos) << swapped;
  EXPECT_NE(swapped.find("subme=1 "), std::string::npos) << swapped;  // superfast's (veryfast: 2)
  ASSERT_EQ(run(transform + " --max-frames 3 --crf 33").code, 0);
  const std::string transformed = x264_settings(out);
  EXPECT_NE(transformed.find("crf=33.0"), std::string::npos) << transformed;
  fs::remove(out);
  for (const auto& [args, option] :
       std::vector<std::pair<std::string, std::string>>{{swap + " --crf 52", "--crf"},
                                                        {swap + " --x264-preset quick", "--x264-preset"},
                                                        {transform + " --crf -1", "--crf"}}) {
    const RunResult r = run(args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(r.out.rfind(option, 0), 0u) << args << ": " << r.out;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  // Without --overlay, track has no video for them.
  EXPECT_NE(run(track.substr(0, track.find(" --overlay")) + " -o " + (dir.path() / "t").string() + " --crf 20").code,
            0);
  EXPECT_FALSE(fs::exists(dir.path() / "t"));
}

}  // namespace facecap
