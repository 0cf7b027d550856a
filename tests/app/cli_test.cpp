// The facecap program end to end: help, exit codes and one-line errors for
// bad inputs and options, the device and the encoder's options.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/refine/compute_device.hpp"
#include "test_support.hpp"

namespace facecap {

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
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--frames"), std::string::npos) << r.out;
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
}

namespace {

// Each command line (first) is refused before any work with exit code 2 and
// its message (second) on the first of two lines: the error, and CLI11's
// pointer to --help.
void expect_refused_by_cli11(std::span<const std::pair<const char*, const char*>> cases) {
  for (const auto& [args, message] : cases) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), message) << args;
    EXPECT_EQ(lines(r.out), 2) << r.out;
  }
}

}  // namespace

// Options that cannot go together, or a command missing what it works on,
// are usage errors as a bad value is: exit 2 before any work (no model is
// loaded, no folder made), the first line naming the option and why.
TEST(Cli, OptionsThatCannotGoTogetherAreRefusedByName) {
  const std::pair<const char*, const char*> cases[] = {
      {"eval refine --video in.mp4 --true-shading",
       "--true-shading: needs --synthetic: real footage has no true shading"},
      {"eval refine --synthetic 2 --save-problems p", "--save-problems: needs --video"},
      {"eval refine --max-frames 3", "eval refine needs --synthetic N or --video PATH"},
      {"eval refine --video in.mp4 --face-photo a.jpg",
       "--face-photo: needs --synthetic: it is the skin of the renders"},
      {"eval track --seed 3", "eval track needs --synthetic N or --video PATH"},
      {"eval track --video in.mp4 --photos 3", "--photos: fits synthetic frames: use it with --synthetic N"},
      {"eval track --synthetic 3 --photos 1 --landmarks dlib",
       "--photos: fits the true landmarks; drop --landmarks dlib"},
      {"eval track --video in.mp4 --true-focal", "--true-focal: needs --synthetic: real footage has no truth to hold"},
      {"eval track --video in.mp4 --true-identity",
       "--true-identity: needs --synthetic: real footage has no truth to hold"},
      {"eval track --synthetic 3 --photos 1 --true-identity",
       "--true-identity: cannot go with --photos, which measures the photos' identities"},
      {"eval track --video in.mp4 --face-photo a.jpg",
       "--face-photo: needs --synthetic: it is the skin of the renders"},
      {"eval landmarks a.png", "eval landmarks needs IMAGE and PTS, a folder of annotated images, or --synthetic N"},
      {"eval landmarks a.png a.pts --face-photo a.jpg",
       "--face-photo: needs --synthetic: it is the skin of the renders"},
      {"eval swap --max-frames 3", "eval swap needs either --self VIDEO, or --source PHOTO and --target VIDEO"},
      {"eval swap --self in.mp4 --target b.mp4",
       "eval swap needs either --self VIDEO, or --source PHOTO and --target VIDEO"},
      {"eval swap --source a.jpg", "--source and --target go together"},
      {"swap --source a.jpg --target b.mp4 -o x.mp4 --all-faces --face-source 1=c.jpg --face-source 1=d.jpg",
       "--face-source: face 1 is given two sources"},
      {"transform in.mp4 -o x.mp4 --all-faces --face-to 1=sadness --face-to 1=anger",
       "face 1 is given two expressions (--face-to, --face-schedule)"},
      {"transform in.mp4 -o x.mp4 --to neutral",
       "--to neutral is the input's expression already (--from neutral), so nothing would change; to take an emotion "
       "away, name it: --from happiness --to neutral"},
      {"transform in.mp4 -o x.mp4 --from sad --to sadness",
       "--to sadness is the input's expression already (--from sadness), so nothing would change; to take an emotion "
       "away, name it: --from happiness --to neutral"},
      {"track in.mp4 -o x --livelink-udp 127.0.0.1:11111 --livelink-subject \"\"",
       "--livelink-subject: must not be empty"},
  };
  expect_refused_by_cli11(cases);
}

// Counts of frames and faces are whole numbers from their least value up:
// anything else is refused before any work, naming the option, the least
// value and what was given (a negative --max-frames once ran the whole input,
// and --synthetic -3 was taken for no --synthetic at all).
TEST(Cli, CountsBelowTheirLeastOrNotWholeAreRefusedByName) {
  const std::pair<const char*, const char*> cases[] = {
      {"track in.mp4 -o x --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"track in.mp4 -o x --max-frames 2.5", "--max-frames: must be a whole number of at least 0, not 2.5"},
      {"transform in.mp4 -o x.mp4 --max-frames -2", "--max-frames: must be a whole number of at least 0, not -2"},
      {"swap --source a.jpg --target b.mp4 -o x.mp4 --max-frames -3",
       "--max-frames: must be a whole number of at least 0, not -3"},
      {"bench track in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"bench swap --source a.jpg --target b.mp4 --max-frames x",
       "--max-frames: must be a whole number of at least 0, not x"},
      {"bench transform in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"eval swap --self in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"eval transform --video in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"eval track --video in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"eval refine --video in.mp4 --max-frames -1", "--max-frames: must be a whole number of at least 0, not -1"},
      {"eval track --synthetic -3", "--synthetic: must be a whole number of at least 1, not -3"},
      {"eval track --synthetic 0", "--synthetic: must be a whole number of at least 1, not 0"},
      {"eval refine --synthetic x", "--synthetic: must be a whole number of at least 1, not x"},
      {"eval landmarks --synthetic -2", "--synthetic: must be a whole number of at least 1, not -2"},
      {"eval track --synthetic 5 --photos -1", "--photos: must be a whole number of at least 1, not -1"},
      {"transform in.mp4 -o x.mp4 --all-faces --leave-faces 1,-2",
       "--leave-faces: must be a whole number of at least 0, not -2"},
      {"track in.mp4 -o x --init-frames 0", "--init-frames: must be a whole number of at least 1, not 0"},
      {"transform in.mp4 -o x.mp4 --init-frames 0", "--init-frames: must be a whole number of at least 1, not 0"},
      {"swap --source a.jpg --target b.mp4 -o x.mp4 --init-frames 0",
       "--init-frames: must be a whole number of at least 1, not 0"},
      {"track in.mp4 -o x --smooth-frames -1", "--smooth-frames: must be a whole number of at least 0, not -1"},
      {"transform in.mp4 -o x.mp4 --smooth-frames -1", "--smooth-frames: must be a whole number of at least 0, not -1"},
      {"swap --source a.jpg --target b.mp4 -o x.mp4 --smooth-frames -1",
       "--smooth-frames: must be a whole number of at least 0, not -1"},
  };
  expect_refused_by_cli11(cases);
  // The help says which values they take.
  EXPECT_NE(run("track --help").out.find("--max-frames INT:NONNEGATIVE"), std::string::npos);
  EXPECT_NE(run("eval track --help").out.find("--synthetic INT:POSITIVE"), std::string::npos);
}

// A FACS edit that cannot be done, or that another option contradicts, a
// crop size without the crops and detail maps without the refinement, are
// refused before any work, by name.
TEST(Cli, FacsEditsCropsAndDetailMapsAreRefusedByNameWhereTheyCannotBeDone) {
  const std::pair<const char*, const char*> cases[] = {
      {"transform in.mp4 -o x.mp4 --units AU25=2",
       "--units: the face model has no shape for AU25 (its units: 1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 18, 20, 22, "
       "24, 26, 28, 45)"},
      {"transform in.mp4 -o x.mp4 --units AU12=9", "--units: AU12's intensity must be between 0 and 5, not 9"},
      {"transform in.mp4 -o x.mp4 --units smile",
       "--units: a unit is AU<number>=<intensity 0-5>, as AU12=3, not \"smile\""},
      {"transform in.mp4 -o x.mp4 --units AU12=3 --to sadness", "--to excludes --units"},
      {"transform in.mp4 -o x.mp4 --units AU12=3 --schedule keys.txt", "--schedule excludes --units"},
      {"transform in.mp4 -o x.mp4 --units AU12=3 --all-faces --face-to 1=anger", "--units excludes --face-to"},
      {"track in.mp4 -o x --aligned-size 64", "--aligned-size requires --aligned-faces"},
      {"track in.mp4 -o x --aligned-faces --aligned-size 8", "--aligned-size: Value 8 not in range 32 to 1024"},
      {"eval transform --video in.mp4 --units AU1=4 --to anger", "--to excludes --units"},
      {"eval transform --video in.mp4 --units AU23=1",
       "--units: the face model has no shape for AU23 (its units: 1, 2, 4, 5, 6, 7, 9, 10, 12, 14, 15, 17, 18, 20, "
       "22, 24, 26, 28, 45)"},
      {"track in.mp4 -o x --detail-maps", "--detail-maps requires --refine"},
      {"track in.mp4 -o x --refine --detail-map-size 512", "--detail-map-size requires --detail-maps"},
      {"track in.mp4 -o x --refine --detail-maps --detail-map-size 16",
       "--detail-map-size: Value 16 not in range 64 to 4096"},
  };
  expect_refused_by_cli11(cases);
}

// Not-a-number and infinity are refused as out of range, where they once
// passed CLI11's range check (NaN fails every comparison) or a "< 0" test:
// `--focal inf` lost every frame and wrote an infinite focal length.
TEST(Cli, NumbersOutOfRangeOrNotNumbersAreRefusedByName) {
  const std::string swap = "swap --source a.jpg --target b.mp4 -o x.mp4 ";
  const std::pair<std::string, std::string> usage[] = {
      {swap + "--residual-shading nan", "--residual-shading: must be a number from 0 to 100, not nan"},
      {swap + "--residual-shading -5", "--residual-shading: must be a number from 0 to 100, not -5"},
      {swap + "--photo-detail nan", "--photo-detail: must be a number from 0 to 1, not nan"},
      {swap + "--photo-detail 1.5", "--photo-detail: must be a number from 0 to 1, not 1.5"},
      {"eval track --synthetic 3 --noise nan", "--noise: must be a number from 0 to 100, not nan"},
      {"eval track --synthetic 3 --noise -1", "--noise: must be a number from 0 to 100, not -1"},
      {"transform in.mp4 -o x.mp4 --to anger --intensity 2", "--intensity: must be a number from 0 to 1, not 2"},
      {"transform in.mp4 -o x.mp4 --to anger --intensity nan", "--intensity: must be a number from 0 to 1, not nan"},
      {"transform in.mp4 -o x.mp4 --window 11", "--window: Value 11 not in range 0 to 10"},
      {"transform in.mp4 -o x.mp4 --lip-weight -1", "--lip-weight: must be a number from 0 to 1e+06, not -1"},
      {"eval transform --video in.mp4 --lip-weight nan", "--lip-weight: must be a number from 0 to 1e+06, not nan"},
      {swap + "--appearance-frames 0", "--appearance-frames: must be a whole number of at least 1, not 0"},
      {swap + "--source-frames 0", "--source-frames: must be a whole number of at least 1, not 0"},
      {"eval swap --self in.mp4 --source-frames 0", "--source-frames: must be a whole number of at least 1, not 0"},
      {"eval refine --synthetic 2 --albedo-frames 0", "--albedo-frames: must be a whole number of at least 1, not 0"},
      {"eval track --synthetic 3 --still-frames -1", "--still-frames: must be a whole number of at least 0, not -1"},
      {"eval track --synthetic 3 --yaw nan", "--yaw: must be a number from 0 to 60, not nan"},
      {"eval track --synthetic 3 --roll 200", "--roll: must be a number from -180 to 180, not 200"},
      {"synth -o x --frames 0", "--frames: must be a whole number of at least 1, not 0"},
      {"synth -o x --fps 0", "--fps: must be a number from 0.1 to 240, not 0"},
      {"synth -o x --focal -1", "--focal: must be a number from 0 to 100000, not -1"},
      {"synth -o x --yaw 90", "--yaw: must be a number from 0 to 60, not 90"},
      {"synth -o x --roll nan", "--roll: must be a number from -180 to 180, not nan"},
      {"synth -o x --noise 60", "--noise: must be a number from 0 to 50, not 60"},
      {"demo --frames -5", "--frames: must be a whole number of at least 1, not -5"},
      {"synth -o x --size huge", "--size: must be WxH, 64 to 8192 a side (as 640x480), not huge"},
      {"synth -o x --size 32x32", "--size: must be WxH, 64 to 8192 a side (as 640x480), not 32x32"},
      {"eval track --synthetic 3 --size 640x", "--size: must be WxH, 64 to 8192 a side (as 640x480), not 640x"},
      {"eval refine --synthetic 3 --size 640x480x2",
       "--size: must be WxH, 64 to 8192 a side (as 640x480), not 640x480x2"},
      {"track in.mp4 -o x --focal nan", "--focal: must be a number from 0 to 100000, not nan"},
      {"track in.mp4 -o x --focal inf", "--focal: must be a number from 0 to 100000, not inf"},
      {"track in.mp4 -o x --focal -3", "--focal: must be a number from 0 to 100000, not -3"},
  };
  for (const auto& [args, message] : usage) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), message) << args;
  }
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
