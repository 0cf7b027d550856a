// facecap's animated glTF opened by Blender's own importer (headless): what
// Blender makes of the file (the morph targets as shape keys under their
// names, the texture, one key per tracked frame) and where its camera sees
// the face at a key, against the file as the glTF specification reads it
// (io/glb_reader.hpp, itself checked against the tracker in
// face_animation_test.cpp). And a refined PLY mesh opened by Blender's PLY
// importer, with its UVs and vertex colours.
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "app/command.hpp"
#include "app/tracked_clip.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/png16.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/model/obj_reader.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "io/glb_reader.hpp"
#include "io/ply_reader.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;
using test::fitted_landmarks;
using test::track_20_frames;

namespace {

// A PNG with its alpha channel, as 8-bit BGRA (facecap's own reader keeps
// only colour); empty when it cannot be read.
cv::Mat read_png_bgra(const fs::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.c_str())) return {};
  image.format = PNG_FORMAT_BGRA;
  cv::Mat bgra(int(image.height), int(image.width), CV_8UC4);
  if (!png_image_finish_read(&image, nullptr, bgra.data, png_int_32(bgra.step), nullptr)) return {};
  return bgra;
}

constexpr int kSubPixelBits = 4;  // for fillConvexPoly

// Where the file's camera sees each vertex of primitive `part` at `key`
// (looking down -z, y up; pixel centres at integers), in pixels times
// 2^kSubPixelBits.
std::vector<cv::Point> projected_part(const test::Glb& g, int part, int key, int width, int height) {
  const Eigen::Matrix3Xf world = g.played_part(part, key);
  std::vector<cv::Point> px(size_t(world.cols()));
  for (Eigen::Index i = 0; i < world.cols(); ++i) {
    const Eigen::Vector2d p = g.camera_pixel(world.col(i), width, height);
    px[size_t(i)] =
        cv::Point(int(std::lround(p.x() * (1 << kSubPixelBits))), int(std::lround(p.y() * (1 << kSubPixelBits))));
  }
  return px;
}

void fill_triangle(cv::Mat& mask, const std::vector<cv::Point>& px, const std::vector<uint32_t>& tris, size_t k) {
  const cv::Point tri[3] = {px[tris[k]], px[tris[k + 1]], px[tris[k + 2]]};
  cv::fillConvexPoly(mask, tri, 3, cv::Scalar(255), cv::LINE_8, kSubPixelBits);
}

// Where the file's primitives cover the image at `key`, seen through its camera.
cv::Mat expected_coverage(const test::Glb& g, int key, int width, int height) {
  cv::Mat mask(height, width, CV_8U, cv::Scalar(0));
  const auto& prims = g.doc.at("meshes").at(0).at("primitives");
  for (size_t part = 0; part < prims.size(); ++part) {
    const std::vector<cv::Point> px = projected_part(g, int(part), key, width, height);
    const std::vector<uint32_t> tris = g.indices(prims.at(part).at("indices"));
    for (size_t k = 0; k + 2 < tris.size(); k += 3) fill_triangle(mask, px, tris, k);
  }
  return mask;
}

// The pixels at `key` that only the face's triangles held out whole by
// `matte` (face_matte.png, read at each corner's UV) cover, and those that
// only its triangles shown whole cover; each shrunk by a pixel.
struct MattedCoverage {
  cv::Mat held_out, shown;
};
MattedCoverage matted_coverage(const test::Glb& g, const cv::Mat& matte, int key, int width, int height) {
  cv::Mat held_out(height, width, CV_8U, cv::Scalar(0)), shown = held_out.clone(), other = held_out.clone();
  const auto& prims = g.doc.at("meshes").at(0).at("primitives");
  for (size_t part = 0; part < prims.size(); ++part) {
    const std::vector<cv::Point> px = projected_part(g, int(part), key, width, height);
    const std::vector<uint32_t> tris = g.indices(prims.at(part).at("indices"));
    std::vector<float> value(px.size(), -1.0f);  // the mouth and eyes: no matte
    if (part == 0) {
      const std::vector<float> uv = g.floats(prims.at(0).at("attributes").at("TEXCOORD_0"));
      for (size_t i = 0; i < value.size(); ++i) {  // glTF's v runs down the image
        cv::Mat sample;
        cv::getRectSubPix(matte, cv::Size(1, 1),
                          cv::Point2f(uv[2 * i] * float(matte.cols) - 0.5f, uv[2 * i + 1] * float(matte.rows) - 0.5f),
                          sample, CV_32F);
        value[i] = sample.at<float>(0, 0);
      }
    }
    for (size_t k = 0; k + 2 < tris.size(); k += 3) {
      const float low = std::min({value[tris[k]], value[tris[k + 1]], value[tris[k + 2]]});
      const float high = std::max({value[tris[k]], value[tris[k + 1]], value[tris[k + 2]]});
      fill_triangle(low >= 0 && high <= 1 ? held_out : low >= 254 ? shown : other, px, tris, k);
    }
  }
  const cv::Mat shrink = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  MattedCoverage out;
  cv::erode(held_out & ~(shown | other), out.held_out, shrink);
  cv::erode(shown & ~(held_out | other), out.shown, shrink);
  return out;
}

// A render (grey, 320x180) of key 17 of `glb` over a plate whose frame 17
// is grey 210: where only the face triangles `matte_png` holds out whole
// cover the frame (the scalp, ears and neck), it shows the plate; where only
// the narrow face does, the face, on average at least `face_off_plate` grey
// levels from the plate. An empty `matte_png`: the file's own matte (the
// image named face_matte).
void expect_held_out_by_matte(const cv::Mat& grey, const fs::path& glb, double face_off_plate,
                              const fs::path& matte_png = {}) {
  const test::Glb g = test::Glb::read(glb);
  cv::Mat matte;
  if (matte_png.empty()) {
    for (size_t i = 0; i < g.doc["images"].size(); ++i)
      if (g.doc["images"][i].value("name", "") == "face_matte") {
        const std::string bytes = g.image_bytes(int(i));
        matte = decode_image({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()});
      }
  } else {
    matte = read_image(matte_png);
  }
  ASSERT_FALSE(matte.empty());
  cv::Mat matte_grey;
  cv::extractChannel(matte, matte_grey, 0);
  const MattedCoverage covered = matted_coverage(g, matte_grey, 17, grey.cols, grey.rows);
  const int held_out = cv::countNonZero(covered.held_out), shown = cv::countNonZero(covered.shown);
  double held_low = 0, held_high = 0;
  cv::minMaxLoc(grey, &held_low, &held_high, nullptr, nullptr, covered.held_out);
  cv::Mat off_the_plate;
  cv::absdiff(grey, cv::Scalar(210), off_the_plate);
  const double face_off_the_plate = cv::mean(off_the_plate, covered.shown)[0];
  std::printf("held out: %d px, grey %.0f-%.0f; shown: %d px, %.1f grey levels from the plate on average\n", held_out,
              held_low, held_high, shown, face_off_the_plate);
  EXPECT_GT(held_out, 300);
  EXPECT_GT(shown, 1000);
  EXPECT_GE(held_low, 206);
  EXPECT_LE(held_high, 214);
  EXPECT_GT(face_off_the_plate, face_off_plate);
}

// Headless Blender with factory settings running a script (then its
// arguments after " -- "), exiting non-zero where the script fails.
const std::string kBlenderScript = "blender -b --factory-startup --python-exit-code 1 --python ";

bool have_blender() { return test::run_command("command -v blender >/dev/null 2>&1").code == 0; }

// Skips the test where Blender cannot run, saying which import goes
// unchecked, or fails it under CI, where setup.sh installs Blender.
#define FACECAP_REQUIRE_BLENDER(what)                                                                \
  if (!have_blender()) {                                                                             \
    if (running_under_ci()) FAIL() << "blender missing under CI (setup.sh installs it)";             \
    GTEST_SKIP() << "blender not installed (setup.sh installs it): " << (what) << " is not checked"; \
  }

// A detail map in millimetres, as detail.json says: (value / 65535 - 0.5) * 2 range.
cv::Mat read_detail_mm(const fs::path& map_file, const fs::path& detail_json) {
  std::ifstream in(detail_json);
  const double range_mm = nlohmann::json::parse(in)["encoding"]["range_mm"];
  const cv::Mat map = read_png16(map_file);
  if (map.empty()) return {};
  cv::Mat mm;
  map.convertTo(mm, CV_32F, 2 * range_mm / 65535, -range_mm);
  return mm;
}

// A map read bilinearly at UV (u, v) as Blender reads an image texture:
// texel x's centre at u = (x + 0.5) / width, v up.
double detail_at(const cv::Mat& mm, double u, double v) {
  cv::Mat sample;
  cv::getRectSubPix(mm, cv::Size(1, 1), cv::Point2f(float(u * mm.cols - 0.5), float((1 - v) * mm.rows - 0.5)), sample);
  return sample.at<float>(0, 0);
}

// A 320 x 180 plate of 20 frames at 29.97 fps whose frame k is a flat grey
// of 40 + 10 k: a render over it shows which of its frames is behind.
void write_grey_plate(const fs::path& file) {
  VideoWriterOptions o;
  o.width = 320;
  o.height = 180;
  o.fps = 30000.0 / 1001.0;
  VideoWriter writer(file, o);
  for (int k = 0; k < 20; ++k) writer.write(cv::Mat(180, 320, CV_8UC3, cv::Scalar::all(40 + 10 * k)));
  writer.finish();
}

// A scene of those 20 frames plays at the video's 29.97 fps over frames
// 0-19, each key on a whole frame (not k * 1.001, where the glTF importer
// put them), and at each probed frame the head is where frames.csv puts it
// (its translation in Blender's axes, z up, in metres: glTF's are the
// camera frame turned half a turn about x; frames.csv keeps 6 digits, 5e-6 m
// here).
void expect_plays_the_video_frame_by_frame(const nlohmann::json& report, const fs::path& frames_csv) {
  EXPECT_NEAR(double(report["fps"]), 30000.0 / 1001.0, 1e-3);
  EXPECT_EQ(report["frame_range"], nlohmann::json({0, 19}));
  const std::vector<double> keyed = report["keyed_frames"];
  ASSERT_EQ(keyed.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(keyed[size_t(k)], double(k));
  const std::vector<std::string> rows = test::read_lines(frames_csv);
  for (const auto& [frame, at] : report["frames"].items()) {
    const std::vector<std::string> row = split_csv_line(rows.at(size_t(std::stoi(frame)) + 1));
    const double tx = std::stod(row[6]), ty = std::stod(row[7]), tz = std::stod(row[8]);
    EXPECT_NEAR(double(at["location"][0]), tx / 100, 1e-5) << frame;
    EXPECT_NEAR(double(at["location"][1]), tz / 100, 1e-5) << frame;
    EXPECT_NEAR(double(at["location"][2]), -ty / 100, 1e-5) << frame;
  }
}

// blender/import_facecap.py run with `arguments`, its scene saved as
// DIR/NAME.blend, then blender_scene_probe.py on the saved scene at `frames`
// (rendering the last into `render`; none for "-"): the probe's report, and
// the import's output in `log`; null where either run failed (reported).
nlohmann::json import_and_probe(const fs::path& dir, const std::string& name, const std::string& arguments,
                                const std::string& render, const std::string& frames, std::string* log = nullptr) {
  const fs::path scene = dir / (name + ".blend"), report = dir / (name + ".json");
  const test::CommandResult imported = test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_IMPORT_SCRIPT) +
                                                         " -- " + arguments + " --save " + scene.string() + " 2>&1");
  if (log != nullptr) *log = imported.out;
  if (imported.code != 0) {
    ADD_FAILURE() << imported.out;
    return nullptr;
  }
  const test::CommandResult probed = test::run_command(
      "blender -b " + scene.string() + " --python-exit-code 1 --python " + std::string(FACECAP_BLENDER_SCENE_PROBE) +
      " -- " + report.string() + " " + render + " " + frames + " 2>&1");
  if (probed.code != 0) {
    ADD_FAILURE() << probed.out;
    return nullptr;
  }
  std::ifstream in(report);
  return nlohmann::json::parse(in);
}

double srgb_to_linear(double byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double intersection_over_union(const cv::Mat& a, const cv::Mat& b) {
  return cv::countNonZero(a & b) / double(std::max(1, cv::countNonZero(a | b)));
}

}  // namespace

TEST(BlenderInterop, TheTrackedGltfOpensWithShapeKeysTextureKeysAndTheCameraView) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_BLENDER("the glTF import");
  // A synthetic performance whose head turns from -15 to 37 degrees of yaw
  // over its 30 frames, so that the keys differ.
  TempDir dir;
  const std::string facecap = std::string(FACECAP_BINARY) + " -q ";
  const test::CommandResult synth =
      test::run_command(facecap + "synth -o " + dir.path().string() + " --frames 30 --size 400x300 2>&1");
  ASSERT_EQ(synth.code, 0) << synth.out;
  const fs::path track = dir.path() / "track";
  const test::CommandResult tracked = test::run_command(facecap + "track " + (dir.path() / "video.mp4").string() +
                                                        " -o " + track.string() + " --refine --gltf 2>&1");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path glb = track / "animation.glb";
  const test::Glb g = test::Glb::read(glb);
  const std::vector<float> times = g.floats(g.doc["animations"][0]["samplers"][0]["input"]);
  ASSERT_EQ(times.size(), 30u);  // no frame lost
  const int key = 12;
  const int width = 400, height = 300;
  const fs::path report_path = dir.path() / "blender.json", render_path = dir.path() / "blender.png";
  const test::CommandResult blender =
      test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_PROBE) + " -- " + glb.string() + " " +
                        report_path.string() + " " + render_path.string() + " " + std::to_string(width) + " " +
                        std::to_string(height) + " " + std::to_string(times[key]) + " 2>&1");
  ASSERT_EQ(blender.code, 0) << blender.out;

  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["cameras"], 1);
  ASSERT_EQ(report["meshes"].size(), 1u);  // the face and its mouth and eyes: one object, two materials
  const auto& mesh = report["meshes"][0];
  size_t vertices = 0;
  for (const auto& prim : g.doc["meshes"][0]["primitives"])
    vertices += size_t(g.doc["accessors"][int(prim["attributes"]["POSITION"])]["count"]);
  EXPECT_EQ(size_t(mesh["vertices"]), vertices);
  std::vector<std::string> names = model->expression_names;
  names.insert(names.end(), kEyeTurnTargetNames.begin(), kEyeTurnTargetNames.end());
  EXPECT_EQ(mesh["shape_keys"].get<std::vector<std::string>>(), names);
  EXPECT_EQ(mesh["materials"], 2);
  EXPECT_EQ(mesh["images"], nlohmann::json::parse("[[1024, 1024]]"));  // the albedo (--refine)
  EXPECT_EQ(size_t(mesh["node_keys"]), times.size());
  EXPECT_EQ(size_t(mesh["shape_key_keys"]), times.size());

  // Blender's render through the imported camera covers what the file says.
  const cv::Mat render = read_png_bgra(render_path);
  ASSERT_EQ(render.type(), CV_8UC4);
  ASSERT_EQ(render.size(), cv::Size(width, height));
  cv::Mat alpha, seen;
  cv::extractChannel(render, alpha, 3);
  cv::threshold(alpha, seen, 127, 255, cv::THRESH_BINARY);
  const cv::Mat expected = expected_coverage(g, key, width, height);
  ASSERT_GT(cv::countNonZero(expected), 0.1 * width * height);  // the face fills a good part of the frame
  // Intersection over union: 0.99 measured.
  EXPECT_GT(intersection_over_union(seen, expected), 0.97);
  // The keys either side cover the image differently enough (0.93, 0.94)
  // that a camera, a pose or a time one frame off would fail that bar.
  for (const int other : {key - 1, key + 1})
    EXPECT_LT(intersection_over_union(expected_coverage(g, other, width, height), expected), 0.97) << other;
}

// track --refine --meshes --mesh-format ply: Blender's PLY importer reads the
// refined finest level with every vertex and triangle, one UV layer and the
// albedo as a colour attribute, which it holds as the file's sRGB bytes
// linearised.
TEST(BlenderInterop, TheRefinedPlyMeshOpensWithItsUvsAndColours) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_BLENDER("the PLY import");
  TempDir dir;
  const test::CommandResult tracked =
      test::run_command(std::string(FACECAP_BINARY) + " -q track " + video.string() + " -o " + dir.path().string() +
                        " --max-frames 32 --refine --meshes --mesh-format ply 2>&1");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path ply_path = dir.path() / "meshes" / "frame_000031.ply";
  const test::Ply ply = test::Ply::read(ply_path);
  const fs::path report_path = dir.path() / "blender.json";
  const test::CommandResult blender =
      test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_PLY_PROBE) + " -- " + ply_path.string() + " " +
                        report_path.string() + " 2>&1");
  ASSERT_EQ(blender.code, 0) << blender.out;
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["meshes"], 1);
  EXPECT_EQ(size_t(report["vertices"]), ply.vertices());
  EXPECT_EQ(size_t(report["faces"]), ply.faces.size());
  EXPECT_EQ(report["uv_layers"], 1);
  ASSERT_EQ(report["colour_attributes"], 1);
  for (int k = 0; k < 3; ++k) {
    const std::vector<double>& bytes = ply.vertex.at(k == 0 ? "red" : k == 1 ? "green" : "blue");
    double mean = 0;
    for (double b : bytes) mean += srgb_to_linear(b);
    mean /= double(bytes.size());
    EXPECT_NEAR(double(report["colour_mean"][k]), mean, 0.002) << "channel " << k;
  }
}

// A refined OBJ frame opens in Blender textured: its material library names
// the capture's albedo.png, which Blender's importer loads as the surface's
// base colour.
TEST(BlenderInterop, TheRefinedObjMeshOpensTexturedWithTheAlbedo) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_BLENDER("the OBJ import");
  TempDir dir;
  const test::CommandResult tracked =
      test::run_command(std::string(FACECAP_BINARY) + " -q track " + video.string() + " -o " + dir.path().string() +
                        " --max-frames 20 --refine --meshes 2>&1");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path report_path = dir.path() / "blender.json";
  const test::CommandResult blender =
      test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_OBJ_PROBE) + " -- " +
                        (dir.path() / "meshes" / "frame_000019.obj").string() + " " + report_path.string() + " 2>&1");
  ASSERT_EQ(blender.code, 0) << blender.out;
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["meshes"], 1);
  EXPECT_GE(int(report["vertices"]), regions::kFace.num_vertices());
  EXPECT_EQ(report["uv_layers"], 1);
  EXPECT_EQ(report["materials"], nlohmann::json::array({"face"}));
  ASSERT_TRUE(report.contains("texture_file")) << report.dump();
  EXPECT_EQ(fs::path(std::string(report["texture_file"])), fs::canonical(dir.path() / "albedo.png"));
  const cv::Mat albedo = read_image((dir.path() / "albedo.png").string());
  EXPECT_EQ(report["texture_size"], nlohmann::json::array({albedo.cols, albedo.rows}));
  EXPECT_EQ(report["texture_is_base_colour"], true);
}

// track --point-cache: Blender's Mesh Cache modifier, with its defaults,
// plays the cache on the imported rest mesh: at scene frame k each vertex
// is where the cache's sample k (the capture's frame k) puts it.
TEST(BlenderInterop, ThePointCachePlaysOnItsRestMeshInBlender) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_BLENDER("the point cache");
  TempDir dir;
  const test::CommandResult tracked =
      test::run_command(std::string(FACECAP_BINARY) + " -q track " + video.string() + " -o " + dir.path().string() +
                        " --max-frames 24 --point-cache --mesh-format ply 2>&1");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path cache = dir.path() / "face.pc2";
  const std::string bytes = test::read_file(cache);
  ASSERT_GE(bytes.size(), 32u);
  int32_t points = 0, samples = 0;
  std::memcpy(&points, bytes.data() + 16, 4);
  std::memcpy(&samples, bytes.data() + 28, 4);
  ASSERT_EQ(samples, 24);
  const std::vector<int> frames = {0, 9, 23}, vertices = {0, 1234, 5000, int(points) - 1};
  const fs::path report_path = dir.path() / "blender.json";
  const test::CommandResult blender = test::run_command(
      kBlenderScript + std::string(FACECAP_BLENDER_PC2_PROBE) + " -- " + (dir.path() / "face_rest.ply").string() + " " +
      cache.string() + " " + report_path.string() + " 0,9,23 0,1234,5000," + std::to_string(points - 1) + " 2>&1");
  ASSERT_EQ(blender.code, 0) << blender.out;
  // The samples differ, so a sample played at another frame would show.
  const auto sample_x = [&](int frame, int vertex) {
    float x;
    std::memcpy(&x, bytes.data() + 32 + (size_t(frame) * size_t(points) + size_t(vertex)) * 12, 4);
    return x;
  };
  EXPECT_GT(std::abs(sample_x(9, 0) - sample_x(0, 0)) + std::abs(sample_x(23, 0) - sample_x(9, 0)), 1e-3);
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(int(report["vertices"]), points);
  for (const int frame : frames) {
    for (size_t k = 0; k < vertices.size(); ++k) {
      float expected[3];
      std::memcpy(expected, bytes.data() + 32 + (size_t(frame) * size_t(points) + size_t(vertices[k])) * 12, 12);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(double(report["frames"][std::to_string(frame)][k][c]), expected[c], 1e-5)
            << "frame " << frame << " vertex " << vertices[k];
    }
  }
}

// track --refine --detail-maps: Blender's Displace modifier, set up as
// detail.json says (the map read as non-colour data), moves each vertex of
// the refined OBJ frame along its normal by the map's displacement at the
// vertex's UV (sampled bilinearly with pixel centres at half-texels, as
// Blender's image textures are).
TEST(BlenderInterop, ADetailMapDisplacesTheRefinedMeshAsDetailJsonSays) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");  // large enough for finer levels
  FACECAP_REQUIRE_BLENDER("the detail maps");
  TempDir dir;
  const test::CommandResult tracked =
      test::run_command(std::string(FACECAP_BINARY) + " -q track " + video.string() + " -o " + dir.path().string() +
                        " --max-frames 20 --refine --meshes --detail-maps 2>&1");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path map_file = dir.path() / "detail" / "frame_000019.png", info = dir.path() / "detail" / "detail.json";
  const fs::path report_path = dir.path() / "blender.json";
  const test::CommandResult blender =
      test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_DISPLACE_PROBE) + " -- " +
                        (dir.path() / "meshes" / "frame_000019.obj").string() + " " + map_file.string() + " " +
                        info.string() + " " + report_path.string() + " 2>&1");
  ASSERT_EQ(blender.code, 0) << blender.out;
  std::ifstream in(report_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["is_float"], true);  // 16 bits read as such, not as 8
  const cv::Mat mm = read_detail_mm(map_file, info);
  ASSERT_FALSE(mm.empty());
  std::vector<double> expected, moved;
  for (size_t v = 0; v < report["moved"].size(); ++v) {
    expected.push_back(detail_at(mm, report["uv"][v][0], report["uv"][v][1]));
    moved.push_back(10.0 * report["moved"][v].get<double>());  // cm to mm
  }
  ASSERT_GT(expected.size(), size_t(2 * regions::kFace.num_vertices()));  // the finest level's
  std::vector<double> error(expected.size());
  for (size_t v = 0; v < expected.size(); ++v) error[v] = std::abs(moved[v] - expected[v]);
  const double corr = pearson_correlation(expected, moved), spread = standard_deviation(expected);
  std::printf("%zu vertices: correlation %.5f, median error %.7f mm (the detail's sd %.4f mm)\n", expected.size(), corr,
              median(error), spread);
  // Measured: correlation 1.0000, median error under 0.000005 mm (sd 0.046 mm).
  EXPECT_GT(spread, 0.005);  // there is detail to displace by
  EXPECT_GT(corr, 0.999);
  EXPECT_LT(median(error), 0.001);
}

// blender/import_facecap.py on a `track --refine --gltf --detail-maps`
// folder, with a plate, the scene saved and opened again: it plays at the
// video's 29.97 fps with video frame N on Blender frame N (the head where
// frames.csv puts it at frames 3 and 17, the plate's frame 17 behind the
// face in a render of frame 17), renders at the input's size, and at each
// frame the detail modifiers move the subdivided face's skin by that frame's
// map, not another's.
TEST(BlenderInterop, TheImportScriptPlaysTheCaptureWithEachFramesDetail) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  FACECAP_REQUIRE_BLENDER("blender/import_facecap.py");
  TempDir dir;
  const test::CommandResult tracked =
      track_20_frames(video, dir.path(), "--refine --gltf --detail-maps --detail-map-size 512");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path plate = dir.path() / "plate.mp4", render = dir.path() / "render.png";
  write_grey_plate(plate);
  std::string log;
  const nlohmann::json report =
      import_and_probe(dir.path(), "scene", dir.path().string() + " --video " + plate.string() + " --subdivisions 1",
                       render.string(), "3 17", &log);
  ASSERT_FALSE(report.is_null());
  EXPECT_NE(log.find("detail maps 000000-000019"), std::string::npos) << log;

  expect_plays_the_video_frame_by_frame(report, dir.path() / "frames.csv");
  EXPECT_EQ(report["camera"], "camera");
  EXPECT_EQ(report["resolution"], nlohmann::json({1280, 720}));  // the input's
  // The camera's axis where facecap's principal point is (W/2, H/2), not at the
  // frame's centre (639.5, 359.5): the lens shifted by half a pixel.
  EXPECT_NEAR(double(report["axis_pixel"][0]), 640.0, 1e-3);
  EXPECT_NEAR(double(report["axis_pixel"][1]), 360.0, 1e-3);
  EXPECT_EQ(report["modifiers"], nlohmann::json::parse(R"([["SUBSURF", "SIMPLE", 1], ["DISPLACE", null, null]])"));
  EXPECT_GT(int(report["skin_vertices"]), 5000);

  const fs::path detail = dir.path() / "detail";
  const cv::Mat maps[2] = {read_detail_mm(detail / "frame_000003.png", detail / "detail.json"),
                           read_detail_mm(detail / "frame_000017.png", detail / "detail.json")};
  ASSERT_FALSE(maps[0].empty());
  ASSERT_FALSE(maps[1].empty());
  for (int which = 0; which < 2; ++which) {
    const int frame = which == 0 ? 3 : 17;
    const nlohmann::json& at = report["frames"][std::to_string(frame)];
    std::vector<double> own_error, other_error;
    for (size_t v = 0; v < at["moved_mm"].size(); ++v) {
      const double moved = at["moved_mm"][v];
      if (moved == 0.0) continue;  // off the skin, or on it where the map reads 0
      own_error.push_back(std::abs(moved - detail_at(maps[which], at["uv"][v][0], at["uv"][v][1])));
      other_error.push_back(std::abs(moved - detail_at(maps[1 - which], at["uv"][v][0], at["uv"][v][1])));
    }
    ASSERT_GT(own_error.size(), 2000u) << frame;  // the probe keeps every 16th vertex
    const auto mean = [](const std::vector<double>& e) {
      return std::accumulate(e.begin(), e.end(), 0.0) / double(e.size());
    };
    const auto worst = [](const std::vector<double>& e) { return *std::max_element(e.begin(), e.end()); };
    std::printf(
        "frame %d: %zu vertices moved; error against its map: mean %.7f, max %.7f mm; "
        "against the other frame's: mean %.4f, max %.4f mm\n",
        frame, own_error.size(), mean(own_error), worst(own_error), mean(other_error), worst(other_error));
    // Measured: at most 0.000006 mm from its own map; from the other
    // frame's, 0.019 mm on average (most of the skin's detail is the same in
    // both, the rest moves) and up to 0.40 mm.
    EXPECT_LT(worst(own_error), 0.0001) << frame;
    EXPECT_GT(mean(other_error), 0.005) << frame;
  }

  // The render of frame 17 has the plate's frame 17 behind the face: a plate
  // whose frame k is a flat grey of 40 + 10 k shows 210 away from the face
  // (frames 16 and 18 would show 200 and 220).
  const cv::Mat rendered = read_image(render.string());
  ASSERT_EQ(rendered.size(), cv::Size(320, 180));
  cv::Mat away(rendered.size(), CV_8U, cv::Scalar(255));
  {
    const cv::Rect face = cv::boundingRect(fitted_landmarks(dir.path() / "frames.jsonl", 17, 0.25f));
    cv::rectangle(away, cv::Rect(face.x - face.width / 2, face.y - face.height, 2 * face.width, 3 * face.height),
                  cv::Scalar(0), cv::FILLED);  // the face and all round it
  }
  cv::Mat grey;
  cv::cvtColor(rendered, grey, cv::COLOR_BGR2GRAY);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(grey, &lowest, &highest, nullptr, nullptr, away);
  std::printf("render of frame 17 away from the face: grey %.0f-%.0f (the plate's frame 17: 210)\n", lowest, highest);
  EXPECT_GE(lowest, 206);
  EXPECT_LE(highest, 214);

  // The face matte holds out the scalp, ears and neck of the model's face
  // region (the file's matte: face_matte.png beside it is the same).
  expect_held_out_by_matte(grey, dir.path() / "animation.glb", 40, dir.path() / "face_matte.png");
  EXPECT_NE(log.find("the face held out by face_matte.png (1 material(s))"), std::string::npos) << log;
}

// import_facecap.py given an animation alone (--glb, as `transform --gltf`
// and `swap --gltf` write them: no frames.csv, no identity.json, no
// face_matte.png beside it) and a plate: the frame rate comes from the keys'
// spacing, the render size from the plate, video frame N still plays on
// Blender frame N, and the matte the file carries holds the face out (in
// the saved scene, reopened to render: the matte is packed into it).
TEST(BlenderInterop, TheImportScriptTakesAnAnimationAlone) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  FACECAP_REQUIRE_BLENDER("blender/import_facecap.py");
  TempDir dir;
  const test::CommandResult tracked = track_20_frames(video, dir.path(), "--gltf");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path alone = dir.path() / "alone";
  fs::create_directories(alone);
  fs::copy_file(dir.path() / "animation.glb", alone / "performance.glb");
  const fs::path plate = dir.path() / "plate.mp4";
  write_grey_plate(plate);
  const fs::path render = dir.path() / "render.png";
  std::string log;
  const nlohmann::json report = import_and_probe(
      dir.path(), "scene", "--glb " + (alone / "performance.glb").string() + " --video " + plate.string(),
      render.string(), "3 17", &log);
  ASSERT_FALSE(report.is_null());
  expect_plays_the_video_frame_by_frame(report, dir.path() / "frames.csv");
  EXPECT_EQ(report["resolution"], nlohmann::json({320, 180}));  // the plate's
  EXPECT_NEAR(double(report["axis_pixel"][0]), 160.0, 1e-3);
  EXPECT_NEAR(double(report["axis_pixel"][1]), 90.0, 1e-3);
  EXPECT_EQ(report["modifiers"], nlohmann::json::array());  // no detail maps
  EXPECT_NE(log.find("the face held out by face_matte.png (1 material(s))"), std::string::npos) << log;
  const cv::Mat rendered = read_image(render);
  ASSERT_EQ(rendered.size(), cv::Size(320, 180));
  cv::Mat grey;
  cv::cvtColor(rendered, grey, cv::COLOR_BGR2GRAY);
  // Not refined, the face is its base colour (0.8, grey 231 under the white
  // world) with its shading, 27.9 levels from the plate's 210 on average.
  expect_held_out_by_matte(grey, alone / "performance.glb", 15);
}

// import_facecap.py on a refined track folder lights the world as the
// refinement found the footage lit (frames.csv's l0..l8, keyed per frame):
// rendered at frame 17, the inner face (landmarks 17-67, eyes and mouth
// left out) is nearer the footage's frame 17 than with --even-light.
TEST(BlenderInterop, TheImportScriptLightsTheFaceAsTheFootageIs) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  FACECAP_REQUIRE_BLENDER("blender/import_facecap.py");
  TempDir dir;
  const test::CommandResult tracked = track_20_frames(video, dir.path(), "--refine --gltf");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  const fs::path lit = dir.path() / "lit.png", even = dir.path() / "even.png";
  std::string log;
  ASSERT_FALSE(import_and_probe(dir.path(), "lit", dir.path().string(), lit.string(), "17", &log).is_null());
  EXPECT_NE(log.find("the world lit as the footage was (20 frames"), std::string::npos) << log;
  EXPECT_EQ(log.find("held out"), std::string::npos) << log;  // no footage behind: the whole region shows
  ASSERT_FALSE(
      import_and_probe(dir.path(), "even", dir.path().string() + " --even-light", even.string(), "17").is_null());

  cv::Mat footage;
  {
    auto source = open_input(video.string());
    Frame f;
    for (int i = 0; i <= 17 && source->read(f); ++i)
      if (i == 17) cv::resize(f.image, footage, cv::Size(320, 180), 0, 0, cv::INTER_AREA);
  }
  ASSERT_FALSE(footage.empty());
  // The inner face at a quarter of the size: the fitted landmarks' hull, less
  // the eyes and the inner mouth (the model's eyeballs and mouth are not skin).
  cv::Mat inner(footage.size(), CV_8U, cv::Scalar(0));
  {
    std::vector<cv::Point> points;
    for (const cv::Point2f& p : fitted_landmarks(dir.path() / "frames.jsonl", 17, 0.25f))
      points.emplace_back(cvRound(p.x), cvRound(p.y));
    std::vector<cv::Point> hull;
    cv::convexHull(std::vector<cv::Point>(points.begin() + 17, points.end()), hull);
    cv::fillConvexPoly(inner, hull, cv::Scalar(255));
    for (const auto& [first, last] : {std::pair{36, 41}, std::pair{42, 47}, std::pair{60, 67}}) {
      const std::vector<cv::Point> part(points.begin() + first, points.begin() + last + 1);
      cv::fillConvexPoly(inner, part, cv::Scalar(0));
      cv::polylines(inner, part, true, cv::Scalar(0), 2);
    }
  }
  double error[2];
  for (int k = 0; k < 2; ++k) {
    const cv::Mat render = read_png_bgra(k == 0 ? lit : even);
    ASSERT_EQ(render.size(), footage.size());
    std::vector<cv::Mat> channels;
    cv::split(render, channels);
    const cv::Mat mask = inner & (channels[3] == 255);
    ASSERT_GT(cv::countNonZero(mask), 1000);
    cv::Mat bgr, difference;
    cv::cvtColor(render, bgr, cv::COLOR_BGRA2BGR);
    cv::absdiff(bgr, footage, difference);
    const cv::Scalar m = cv::mean(difference, mask);
    error[k] = (m[0] + m[1] + m[2]) / 3;
  }
  std::printf("inner face against the footage: %.2f grey levels lit as the footage was, %.2f lit evenly\n", error[0],
              error[1]);
  // Measured: 10.94 against 18.99 (10.68 and 18.68 before the lens shift
  // onto facecap's principal point). With the world's x, y or z turned the
  // other way, 12.82, 16.60 and 22.35; without the bands' scaling (what a
  // Lambertian surface needs), 10.36, as near: Cycles' self-shadowing, which
  // SH shading lacks, blurs that difference (on a convex sphere the scaling
  // is what matches: TheFootageLightShadesASphereAsFacecapsShadingDoes).
  EXPECT_LT(error[0], 11.5);
  EXPECT_LT(error[0], 0.8 * error[1]);
}

// track --chan: Blender's Nuke .chan add-on, reading head.chan onto an Axis
// (an empty) and camera.chan onto a camera as Nuke's defaults say (rotation
// order ZXY), sees the model-space meshes under the head where the fit put
// the landmarks: the inner landmark vertices of frames 3 and 17 project onto
// frames.jsonl's fitted landmarks, half a pixel up and left (the frame's
// centre against facecap's principal point). Read in another order, they
// do not.
TEST(BlenderInterop, TheChanFilesPutTheMeshesWhereTheFitSawThem) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  FACECAP_REQUIRE_BLENDER("the .chan files");
  TempDir dir;
  const test::CommandResult tracked = track_20_frames(video, dir.path(), "--chan --meshes");
  ASSERT_EQ(tracked.code, 0) << tracked.out;
  nlohmann::json points;
  for (const int frame : {3, 17}) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.obj", frame);
    const ObjData mesh = read_obj(dir.path() / "meshes" / name, {.read_topology = false});
    nlohmann::json& at = points[std::to_string(frame + 1)];  // Nuke's frame numbers start at 1
    for (int i = 17; i < 68; ++i) {
      const size_t v = size_t(model->landmarks.vertices[size_t(i)]);
      at.push_back({mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]});
    }
  }
  const fs::path points_path = dir.path() / "points.json";
  std::ofstream(points_path) << points.dump();
  double worst[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const fs::path report_path = dir.path() / "pixels.json";
    const test::CommandResult probed =
        test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_CHAN_PROBE) + " -- " + report_path.string() +
                          " " + (dir.path() / "head.chan").string() + " " + (dir.path() / "camera.chan").string() +
                          " 1280 720 " + points_path.string() + (k == 0 ? " ZXY" : " XYZ") + " 2>&1");
    ASSERT_EQ(probed.code, 0) << probed.out;
    std::ifstream in(report_path);
    const nlohmann::json pixels = nlohmann::json::parse(in);
    for (const int frame : {3, 17}) {
      const std::vector<cv::Point2f> fitted = fitted_landmarks(dir.path() / "frames.jsonl", frame, 1.0f);
      const nlohmann::json& seen = pixels.at(std::to_string(frame + 1));
      ASSERT_EQ(seen.size(), 51u);
      for (size_t i = 0; i < 51; ++i) {
        // facecap's principal point is (W / 2, H / 2) with pixel centres at
        // integers, half a pixel right of and below the frame's centre,
        // where Blender's (and Nuke's) camera puts it.
        const cv::Point2f p(float(seen[i][0]) + 0.5f, float(seen[i][1]) + 0.5f);
        worst[k] = std::max(worst[k], double(cv::norm(p - fitted[17 + i])));
      }
    }
  }
  std::printf(
      "inner landmarks through the .chan camera: at most %.3f px from the fit's (order ZXY), %.2f px read "
      "as XYZ\n",
      worst[0], worst[1]);
  // Measured: 0.007 px (the files' 6 decimals); 3.6 px in the wrong order.
  EXPECT_LT(worst[0], 0.02);
  EXPECT_GT(worst[1], 1.0);
}

// The footage light (add_footage_light) is what facecap's shading assumes:
// a white Lambertian sphere, convex so that nothing shadows it, rendered by
// Cycles under the world made from lighting l shows facecap's own l^T SH(n)
// (core/spherical_harmonics.hpp) at each normal it faces the camera with.
// The world's radiance with each band as l gives it, not scaled back by the
// cosine lobe's A_l / pi, does not.
TEST(BlenderInterop, TheFootageLightShadesASphereAsFacecapsShadingDoes) {
  FACECAP_REQUIRE_BLENDER("the footage light");
  TempDir dir;
  // A light from above right and toward the camera, with every band-2 term
  // (the world's radiance stays positive everywhere, as a world's must).
  const ShCoeffs l = (ShCoeffs() << 0.6, 0.06, 0.05, 0.08, 0.03, -0.02, 0.03, 0.025, 0.02).finished();
  ShCoeffs unscaled = l;  // what a radiance of l's own coefficients lights as
  unscaled.segment<3>(1) /= 1.5;
  unscaled.tail<5>() /= 4.0;
  double rms[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const ShCoeffs& world = k == 0 ? l : unscaled;
    const fs::path report_path = dir.path() / ("sphere" + std::to_string(k) + ".json");
    std::string arguments;
    for (int i = 0; i < 9; ++i) arguments += " " + std::to_string(world[i]);
    const test::CommandResult probed = test::run_command(kBlenderScript + std::string(FACECAP_BLENDER_LIGHT_PROBE) +
                                                         " -- " + std::string(FACECAP_BLENDER_IMPORT_SCRIPT) + " " +
                                                         report_path.string() + arguments + " 2>&1");
    ASSERT_EQ(probed.code, 0) << probed.out;
    std::ifstream in(report_path);
    const nlohmann::json samples = nlohmann::json::parse(in)["samples"];
    ASSERT_GT(samples.size(), 2000u);  // the sphere's disc, inside 0.9 of its radius, at 64 x 64
    double sum = 0;
    for (const auto& s : samples) {
      // The pixel's normal in facecap's viewer frame (x right, y up, z toward the viewer).
      const double x = s[0], y = s[1], z = std::sqrt(1 - x * x - y * y);
      const double rendered = (double(s[2]) + double(s[3]) + double(s[4])) / 3;
      sum += std::pow(rendered - sh_shade(l, x, y, z), 2);
    }
    rms[k] = std::sqrt(sum / double(samples.size()));
  }
  std::printf("sphere against l^T SH(n): RMS %.4f with the footage light, %.4f with the bands unscaled\n", rms[0],
              rms[1]);
  // Measured: 0.0028 (Cycles' noise at 1024 samples; the shading is about
  // 0.6) against 0.039; band 1 alone unscaled 0.024, band 2 alone 0.020.
  EXPECT_LT(rms[0], 0.006);
  EXPECT_GT(rms[1], 0.012);
}

// import_facecap.py on a folder that is not there, one without its
// animation or with a corrupt one, or with a video that is not there:
// Blender exits non-zero with one line naming what is wrong.
TEST(BlenderInterop, TheImportScriptNamesWhatIsWrongInOneLine) {
  FACECAP_REQUIRE_BLENDER("blender/import_facecap.py");
  TempDir dir;
  const std::string script = kBlenderScript + std::string(FACECAP_BLENDER_IMPORT_SCRIPT) + " -- ";
  const fs::path missing = dir.path() / "nowhere", animation = dir.path() / "animation.glb";
  const auto refused = [&](const std::string& arguments, const std::string& line) {
    const test::CommandResult r = test::run_command(script + arguments + " 2>&1");
    EXPECT_NE(r.code, 0) << arguments;
    EXPECT_NE(r.out.find("import_facecap: " + line), std::string::npos) << r.out;
  };
  refused(missing.string(), missing.string() + " is not a folder\n");
  refused(dir.path().string(), animation.string() + " not found");
  std::ofstream(animation) << "not a glTF";
  refused(dir.path().string() + " --video " + (dir.path() / "take.mp4").string(),
          (dir.path() / "take.mp4").string() + " not found\n");
  refused(dir.path().string(), "cannot read " + animation.string() + ": ");

  // A good animation (one textured triangle before the camera, two keys),
  // with a face matte cut short (beside it, or in it), or a video that is no video.
  GltfAnimatedMesh m;
  {
    m.name = "face";
    GltfPrimitive triangle;
    triangle.name = "face";
    triangle.positions = (Positions(3, 3) << -0.1f, 0.1f, 0.0f, -0.1f, -0.1f, 0.1f, -1, -1, -1).finished();
    triangle.uvs = (Eigen::Matrix2Xf(2, 3) << 0, 1, 0, 1, 1, 0).finished();
    triangle.triangles = {{0, 1, 2}};
    triangle.morph_targets = {Positions::Zero(3, 3)};
    m.primitives = {triangle};
    m.morph_target_names = {"jawOpen"};
    m.times = {0.0f, 1 / 30.0f};
    m.translations = {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
    m.rotations = {Eigen::Quaternionf::Identity(), Eigen::Quaternionf::Identity()};
    m.weights = Eigen::MatrixXf::Zero(1, 2);
    m.camera = GltfCamera{};
    write_glb(animation, m);
  }
  const std::string bytes = test::read_file(FACECAP_BLENDER_IMPORT_SCRIPT);  // any file that is not a PNG
  const std::string cut_png = "\x89PNG\r\n\x1a\n" + bytes.substr(0, 100);
  std::ofstream(dir.path() / "face_matte.png", std::ios::binary) << cut_png;
  const fs::path plate = dir.path() / "plate.mp4";  // the matte is read where there is footage behind
  write_grey_plate(plate);
  refused(dir.path().string() + " --video " + plate.string(),
          "cannot read " + (dir.path() / "face_matte.png").string() + ": not an image");
  {
    const fs::path carrying = dir.path() / "carrying.glb";
    GltfAnimatedMesh with_matte = m;
    with_matte.images = {{"face_matte", std::vector<uint8_t>(cut_png.begin(), cut_png.end())}};
    write_glb(carrying, with_matte);
    refused("--glb " + carrying.string() + " --video " + plate.string(),
            "cannot read the face matte in " + carrying.string() + ": not an image");
  }
  {  // the animation and the plate are good: left alone, the matte is not read
    const test::CommandResult whole =
        test::run_command(script + dir.path().string() + " --video " + plate.string() + " --whole-face 2>&1");
    EXPECT_EQ(whole.code, 0) << whole.out;
    EXPECT_NE(whole.out.find("import_facecap: animation.glb at 30.000 fps, frames 0-1"), std::string::npos)
        << whole.out;
  }
  std::ofstream(dir.path() / "take.mp4", std::ios::binary) << std::string(5000, '\0');
  refused(dir.path().string() + " --whole-face --video " + (dir.path() / "take.mp4").string(),
          "cannot read " + (dir.path() / "take.mp4").string() + ": no frames");
}

}  // namespace facecap
