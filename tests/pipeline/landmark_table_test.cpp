// track --landmarks-csv (landmark_table.hpp): each frame's detected, fitted
// and 3D landmarks in OpenFace's columns, the 3D points against a synthetic
// render's true landmark vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "facecap/core/csv_line.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/model/obj_reader.hpp"
#include "facecap/pipeline/landmark_table.hpp"
#include "facecap/pipeline/track_job.hpp"
#include "facecap/synth/synthesize.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// Column of a landmark's field: `group` 0..6 for x, y, fit_x, fit_y, X, Y, Z.
size_t column(int group, int landmark) { return 3 + size_t(group) * kNumLandmarks + size_t(landmark); }

double field(const std::vector<std::string>& row, int group, int landmark) {
  return std::stod(row.at(column(group, landmark)));
}

}  // namespace

TEST(LandmarkTable, PutsEachLandmarkUnderItsOpenFaceColumn) {
  const std::vector<std::string> header = split_csv_line(landmark_table_header());
  ASSERT_EQ(header.size(), 3u + 7u * kNumLandmarks);
  EXPECT_EQ(header[0], "frame");
  EXPECT_EQ(header[2], "status");
  EXPECT_EQ(header[column(0, 0)], "x_0");
  EXPECT_EQ(header[column(1, 0)], "y_0");
  EXPECT_EQ(header[column(2, 30)], "fit_x_30");
  EXPECT_EQ(header[column(3, 67)], "fit_y_67");
  EXPECT_EQ(header[column(4, 0)], "X_0");
  EXPECT_EQ(header.back(), "Z_67");

  CoarseFit fit;
  for (int i = 0; i < kNumLandmarks; ++i) {
    fit.observed[i] = Vec2f(100.0f + i, 200.5f + i);
    fit.fitted[i] = Vec2f(101.25f + i, 199.0f - i);
    fit.fitted_points[i] = Vec3d(0.1 * i, -2.5, 60.0 + i);  // cm
  }
  const std::vector<std::string> row = split_csv_line(landmark_table_row(7, 0.25, "tracked", &fit));
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(row[0], "7");
  EXPECT_EQ(row[1], "0.25");
  EXPECT_EQ(row[2], "tracked");
  EXPECT_DOUBLE_EQ(field(row, 0, 5), 105.0);
  EXPECT_DOUBLE_EQ(field(row, 1, 5), 205.5);
  EXPECT_DOUBLE_EQ(field(row, 2, 5), 106.25);
  EXPECT_DOUBLE_EQ(field(row, 3, 5), 194.0);
  EXPECT_DOUBLE_EQ(field(row, 4, 5), 5.0);  // millimetres
  EXPECT_DOUBLE_EQ(field(row, 5, 5), -25.0);
  EXPECT_DOUBLE_EQ(field(row, 6, 5), 650.0);

  const std::vector<std::string> lost = split_csv_line(landmark_table_row(8, 0.5, "lost", nullptr));
  ASSERT_EQ(lost.size(), header.size());
  EXPECT_EQ(lost[2], "lost");
  for (size_t k = 3; k < lost.size(); ++k) EXPECT_TRUE(lost[k].empty()) << header[k];
}

// A capture of a synthetic render: the detected columns are frames.jsonl's
// landmarks, the fitted ones the 3D points projected with the fitted focal
// length, the 3D points those of the frame's mesh (--meshes in camera space),
// and they lie where the render's landmark vertices were, as near as the fit
// from dlib's landmarks on these renders comes (docs/open-bars.md).
TEST(LandmarkTable, TheFittedPointsLieOnTheRendersLandmarkVertices) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  SynthOptions so;
  so.frames = 40;
  so.seed = 3;
  const SynthJobResult synth = synthesize(*model, so, dir.path() / "synth", true);
  TrackOptions o;
  o.capture.quiet = true;
  o.landmarks_csv = true;
  o.meshes = true;
  o.mesh_space = MeshSpace::kCamera;
  const TrackSummary s = run_track(*model, synth.video.string(), dir.path() / "track", o);
  ASSERT_EQ(s.capture.lost, 0);
  EXPECT_EQ(s.capture.identity.frames_used, 30);

  const std::vector<std::string> lines = test::read_lines(dir.path() / "track" / "landmarks.csv");
  const std::vector<std::string> jsonl = test::read_lines(dir.path() / "track" / "frames.jsonl");
  ASSERT_EQ(lines.size(), size_t(so.frames) + 1);
  ASSERT_EQ(jsonl.size(), size_t(so.frames));
  EXPECT_EQ(lines[0], landmark_table_header());
  const SynthPerformance& perf = synth.ground_truth.performance;
  const double focal = s.capture.identity.focal;
  const PinholeCamera camera = PinholeCamera::centered(focal, so.width, so.height);
  double reprojection_px = 0, mesh_difference_mm = 0, centred_error_mm = 0, depth_error_rel = 0,
         eye_distance_error_rel = 0;
  int inner_points = 0;
  for (int f = 0; f < so.frames; ++f) {
    const std::vector<std::string> row = split_csv_line(lines[size_t(f) + 1]);
    ASSERT_EQ(row.size(), 3u + 7u * kNumLandmarks);
    ASSERT_NE(row[2], "lost");
    const nlohmann::json j = nlohmann::json::parse(jsonl[size_t(f)]);
    for (int i = 0; i < kNumLandmarks; ++i) {
      EXPECT_NEAR(field(row, 0, i), j["landmarks"][i][0].get<double>(), 0.01);
      EXPECT_NEAR(field(row, 1, i), j["landmarks"][i][1].get<double>(), 0.01);
      EXPECT_NEAR(field(row, 2, i), j["fitted_landmarks"][i][0].get<double>(), 0.01);
      const Vec3d mm(field(row, 4, i), field(row, 5, i), field(row, 6, i));
      const Vec2d projected = camera.project(Vec3d(mm / 10.0));
      reprojection_px = std::max(reprojection_px, (projected - Vec2d(field(row, 2, i), field(row, 3, i))).norm());
    }
    char mesh_name[32];
    std::snprintf(mesh_name, sizeof(mesh_name), "frame_%06d.obj", f);
    const ObjData mesh = read_obj(dir.path() / "track" / "meshes" / mesh_name);
    for (int i = 17; i < kNumLandmarks; ++i)
      for (int axis = 0; axis < 3; ++axis)
        mesh_difference_mm =
            std::max(mesh_difference_mm,
                     std::abs(field(row, 4 + axis, i) -
                              10.0 * mesh.positions[3 * size_t(model->landmarks.vertices[size_t(i)]) + size_t(axis)]));
    // The true points of the landmarks with fixed vertices (17-67: the jaw's
    // follow the outline), in camera space, against the table's, each set
    // about its centroid (the depth of a monocular face is only as good as
    // its size: sizes and depths scale together).
    const SynthFrame& truth = perf.frames[size_t(f)];
    const Positions shape = model->evaluate(perf.identity, truth.expression, regions::kFace);
    const Mat3d r = truth.pose.model_to_camera_rotation();
    Eigen::Matrix3Xd true_mm(3, kNumLandmarks - 17), fitted_mm(3, kNumLandmarks - 17);
    for (int i = 17; i < kNumLandmarks; ++i) {
      true_mm.col(i - 17) =
          10.0 * (r * shape.col(model->landmarks.vertices[size_t(i)]).cast<double>() + truth.pose.translation);
      fitted_mm.col(i - 17) = Vec3d(field(row, 4, i), field(row, 5, i), field(row, 6, i));
    }
    depth_error_rel += std::abs(fitted_mm.row(2).mean() / true_mm.row(2).mean() - 1.0);
    const auto eye_distance = [](const Eigen::Matrix3Xd& p) { return (p.col(36 - 17) - p.col(45 - 17)).norm(); };
    eye_distance_error_rel += std::abs(eye_distance(fitted_mm) / eye_distance(true_mm) - 1.0);
    const Eigen::Matrix3Xd d =
        (fitted_mm.colwise() - fitted_mm.rowwise().mean()) - (true_mm.colwise() - true_mm.rowwise().mean());
    centred_error_mm += d.colwise().norm().sum();
    inner_points += int(d.cols());
  }
  centred_error_mm /= inner_points;
  depth_error_rel /= so.frames;
  eye_distance_error_rel /= so.frames;
  EXPECT_LT(reprojection_px, 0.01);     // measured 0.0009
  EXPECT_LT(mesh_difference_mm, 0.01);  // 0.0005: the OBJ's 5 decimals of a centimetre
  // Measured 7.4 mm, 4.6 % and 9 %: dlib's points on these renders lie 3 % of
  // the eye distance from the model's (docs/open-bars.md). Millimetres read
  // as centimetres, or a flipped axis, would be off by tens of millimetres.
  EXPECT_LT(centred_error_mm, 10.0);
  EXPECT_LT(depth_error_rel, 0.07);
  EXPECT_LT(eye_distance_error_rel, 0.12);
}

}  // namespace facecap
