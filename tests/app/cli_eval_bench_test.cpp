// facecap demo, eval and bench end to end: their JSON reports, and results
// that do not depend on the thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "facecap/core/temp_dir.hpp"
#include "test_support.hpp"

namespace facecap {

// eval track --photos fits each K-th synthetic frame alone and reports the
// photos' identity errors as JSON (with real footage or dlib's landmarks it
// is a usage error: Cli.OptionsThatCannotGoTogetherAreRefusedByName).
TEST(Cli, EvalTrackFitsSyntheticFramesAsPhotos) {
  FACECAP_REQUIRE_MODEL(model);
  const nlohmann::json j = json_from("eval track --synthetic 6 --photos 3 --size 640x480");
  EXPECT_EQ(j.at("photos"), 2) << j.dump();
  EXPECT_GT(j.at("shape_error_mm").get<double>(), 0.0);
  EXPECT_LT(j.at("shape_error_mm").get<double>(), 5.0);
}

// eval transform --units: a FACS edit's report, unit by unit in the order
// asked, with the emotion's keys null; the units it set are what was asked
// in the output, and the output tracked again shows the raised brows.
TEST(Cli, EvalTransformReportsAFacsEditUnitByUnit) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const nlohmann::json j =
      json_from("eval transform --video " + video.string() + " --units AU1=4,AU4=0 --max-frames 40");
  EXPECT_EQ(j.at("method"), "facs-units") << j.dump();
  EXPECT_EQ(j.at("lip_weight"), 10.0);  // the paper's alpha, for positions in cm
  EXPECT_TRUE(j.at("to").is_null());
  EXPECT_TRUE(j.at("target_rise").is_null());
  EXPECT_TRUE(j.at("retracked_rise").is_null());
  EXPECT_EQ(j.at("marked_synthetic"), true);
  EXPECT_LT(j.at("lip_error_mm").get<double>(), 1.0);
  const nlohmann::json& units = j.at("units");
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[0].at("unit"), "AU01");
  EXPECT_EQ(units[0].at("name"), "inner brow raiser");
  EXPECT_EQ(units[1].at("unit"), "AU04");
  EXPECT_EQ(units[0].at("asked"), 4.0);
  EXPECT_NEAR(units[0].at("output").get<double>(), 4.0, 0.02);
  EXPECT_NEAR(units[1].at("output").get<double>(), 0.0, 0.02);
  EXPECT_GT(units[0].at("retracked").get<double>(), units[0].at("input").get<double>() + 0.5);
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

}  // namespace facecap
