// DetailMaps (track --refine --detail-maps): what a map holds at each texel,
// against a displacement known in closed form, and what its folder keeps.
#include "facecap/pipeline/detail_maps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/png16.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/synth/wrinkles.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// The mean face's region in model space (cm).
Positions mean_face(const FaceModel& model) {
  const Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
  return neutral.leftCols(regions::kFace.num_vertices());
}

// The hierarchy a 1280 x 720 frame builds of the mean face 60 cm from the
// camera, looking at it (X_camera = diag(1, -1, -1) X_model + (0, 0, 60)).
MeshHierarchy frontal_hierarchy(const FaceModel& model) {
  Positions camera_space = mean_face(model);
  camera_space.row(1) *= -1;
  camera_space.row(2) = 60.0f - camera_space.row(2).array();
  return MeshHierarchy::build(model.region_polygons(regions::kFace), regions::kFace.num_vertices(), camera_space,
                              PinholeCamera::centered(1400, 1280, 720));
}

// The synthetic renders' wrinkles (synth/wrinkles.hpp), cm, at each vertex of
// the finest level, placed on the mean face by the hierarchy's own stencils.
Eigen::VectorXf finest_wrinkles(const FaceModel& model, const MeshHierarchy& h) {
  const Eigen::MatrixXf place = h.prolong_from_coarse(mean_face(model), h.num_levels() - 1);
  Eigen::VectorXf d(place.cols());
  for (Eigen::Index v = 0; v < place.cols(); ++v) d[v] = wrinkle_displacement(Vec3f(place.col(v)));
  return d;
}

// `displacement_cm` baked by DetailMaps into DIR/detail as frame 0's map,
// `size` texels square, and read back.
cv::Mat baked_map(const FaceModel& model, const MeshHierarchy& h, const Eigen::VectorXf& displacement_cm,
                  const fs::path& dir, int size) {
  DetailMaps maps(model, dir, size);
  maps.add(0, h, displacement_cm);
  maps.finish();
  return read_png16(dir / "detail" / "frame_000000.png");
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace

// Each texel holds the wrinkles' depth at the surface point the model's own
// UVs put there: the point found through the coarse mesh's per-corner UVs
// (rasterised on their own, not through the hierarchy's prolonged UVs), the
// depth evaluated there in closed form. What differs is the finest level's
// piecewise-linear sampling of the wrinkles and the 16-bit quantisation.
TEST(DetailMaps, EachTexelHoldsTheDepthAtItsPointOfTheFace) {
  FACECAP_REQUIRE_MODEL(model);
  const MeshHierarchy h = frontal_hierarchy(*model);
  const Eigen::VectorXf wrinkles = finest_wrinkles(*model, h);
  TempDir dir;
  constexpr int kSize = 1024;
  const cv::Mat map = baked_map(*model, h, wrinkles, dir.path(), kSize);
  ASSERT_EQ(map.type(), CV_16UC1);
  ASSERT_EQ(map.rows, kSize);

  const TriangleMesh coarse = model->region_mesh(regions::kFace);
  const UvTexelMap texels = rasterize_uv(coarse, kSize);
  const Positions face = mean_face(*model);
  const DetailEncoding encoding;
  std::vector<double> truth, baked, wrinkle_error;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const int i = texels.index(x, y);
      if (texels.triangle[i] < 0) continue;
      const Vec3f point = texels.interpolate(coarse.triangles, face, i);
      truth.push_back(10.0 * wrinkle_displacement(point));
      baked.push_back(encoding.decode(map.at<uint16_t>(y, x)));
      if (std::abs(truth.back()) > 0.05) wrinkle_error.push_back(std::abs(baked.back() - truth.back()));
    }
  ASSERT_GT(wrinkle_error.size(), 10000u);
  const double corr = pearson_correlation(truth, baked);
  const double median_error = median(wrinkle_error);
  std::printf("texels %zu (wrinkles %zu): correlation %.4f, median error on the wrinkles %.4f mm\n", truth.size(),
              wrinkle_error.size(), corr, median_error);
  // Measured: 0.9968 and 0.0093 mm of wrinkles 0.3-0.9 mm deep, over a
  // million texels (the face region fills 95 % of ICT's UV square).
  EXPECT_GT(corr, 0.99);
  EXPECT_LT(median_error, 0.02);
}

// What a renderer reads: sampled bilinearly where Blender, three.js and
// OpenGL put texel centres (u = (x + 0.5) / N; written out here, not taken
// from facecap's own conversion), the map gives each finest-level vertex its
// own depth. Baking texel x at u = x / (N - 1), as facecap did before
// 2026-12-01, left every value up to half a texel from where a renderer
// reads it: median error 0.0065 mm at 1024 against 0.0042 now.
TEST(DetailMaps, ARendererReadsEachVertexsDepthAtItsUv) {
  FACECAP_REQUIRE_MODEL(model);
  const MeshHierarchy h = frontal_hierarchy(*model);
  const Eigen::VectorXf wrinkles = finest_wrinkles(*model, h);
  TempDir dir;
  constexpr int kSize = 1024;
  const cv::Mat map = baked_map(*model, h, wrinkles, dir.path(), kSize);
  ASSERT_EQ(map.type(), CV_16UC1);
  cv::Mat mm;
  const DetailEncoding encoding;
  map.convertTo(mm, CV_32F, 1.0 / encoding.scale(), -DetailEncoding::kOffset / encoding.scale());
  const std::vector<Vec2f> uv =
      per_vertex_uvs(level_uv_mesh(h, h.num_levels() - 1, per_vertex_uvs(model->region_mesh(regions::kFace))));
  std::vector<double> error;
  for (size_t v = 0; v < uv.size(); ++v) {
    const double truth = 10.0 * wrinkles[Eigen::Index(v)];
    if (std::abs(truth) <= 0.05) continue;
    cv::Mat read;
    cv::getRectSubPix(mm, cv::Size(1, 1), cv::Point2f(uv[v].x() * kSize - 0.5f, (1.0f - uv[v].y()) * kSize - 0.5f),
                      read, CV_32F);
    error.push_back(std::abs(double(read.at<float>(0, 0)) - truth));
  }
  ASSERT_GT(error.size(), 2000u);  // 2251 of the finest level's vertices
  const double median_error = median(error);
  std::printf("vertices on the wrinkles %zu: median error %.4f mm\n", error.size(), median_error);
  EXPECT_LT(median_error, 0.005);
}

// detail.json says how to read the maps and what they hold; an earlier run's
// map of a frame this run did not write is removed, other files are kept.
TEST(DetailMaps, TheFolderHoldsThisRunsMapsAndSaysHowToReadThem) {
  FACECAP_REQUIRE_MODEL(model);
  const MeshHierarchy h = frontal_hierarchy(*model);
  const Eigen::VectorXf wrinkles = finest_wrinkles(*model, h);
  TempDir dir;
  {
    DetailMaps earlier(*model, dir.path(), 128);
    earlier.add(0, h, wrinkles);
    earlier.add(1, h, wrinkles);
    earlier.finish();
  }
  std::ofstream(dir.path() / "detail" / "notes.txt") << "mine\n";
  DetailMaps maps(*model, dir.path(), 128);
  maps.add(0, h, 2 * wrinkles);
  maps.finish();
  EXPECT_TRUE(fs::exists(dir.path() / "detail" / "frame_000000.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "detail" / "frame_000001.png"));
  EXPECT_TRUE(fs::exists(dir.path() / "detail" / "notes.txt"));

  const nlohmann::json j = read_json(dir.path() / "detail" / "detail.json");
  EXPECT_EQ(j.at("format"), "facecap-detail-maps");
  EXPECT_EQ(j.at("maps"), 1);
  EXPECT_EQ(j.at("size"), nlohmann::json({128, 128}));
  const double range = j.at("encoding").at("range_mm");
  EXPECT_EQ(range, DetailEncoding{}.range_mm);
  EXPECT_NEAR(j.at("blender_displace").at("strength_cm").get<double>(), 2 * range / 10, 1e-12);
  EXPECT_NEAR(j.at("displacement_mm").at("max").get<double>(), 20.0 * wrinkles.maxCoeff(), 1e-5);
  EXPECT_NEAR(j.at("displacement_mm").at("min").get<double>(), 20.0 * wrinkles.minCoeff(), 1e-5);
  EXPECT_NEAR(j.at("displacement_mm").at("rms").get<double>(),
              20.0 * std::sqrt(wrinkles.squaredNorm() / wrinkles.size()), 1e-5);
  EXPECT_EQ(j.at("encoding").at("clamped_fraction"), 0.0);

  // A run that wrote no map (no face found) says so, with no extremes.
  TempDir empty;
  DetailMaps none(*model, empty.path(), 64);
  none.finish();
  const nlohmann::json nothing = read_json(empty.path() / "detail" / "detail.json");
  EXPECT_EQ(nothing.at("maps"), 0);
  EXPECT_TRUE(nothing.at("displacement_mm").is_null());
}

// A frame without a refined face gets a flat map (0 mm everywhere), so that
// the maps make an unbroken image sequence for Blender and compositors;
// detail.json counts them, and their zeros stay out of the extremes.
TEST(DetailMaps, AFrameWithoutAFaceGetsAFlatMap) {
  FACECAP_REQUIRE_MODEL(model);
  const MeshHierarchy h = frontal_hierarchy(*model);
  const Eigen::VectorXf wrinkles = finest_wrinkles(*model, h);
  TempDir dir;
  DetailMaps maps(*model, dir.path(), 64);
  maps.add(0, h, wrinkles);
  maps.add_flat(1);
  maps.add(2, h, wrinkles);
  maps.finish();
  EXPECT_EQ(maps.maps_written(), 3);
  EXPECT_EQ(maps.flat_maps_written(), 1);
  const cv::Mat flat = read_png16(dir.path() / "detail" / "frame_000001.png");
  ASSERT_EQ(flat.type(), CV_16UC1);
  ASSERT_EQ(flat.size(), cv::Size(64, 64));
  EXPECT_EQ(cv::countNonZero(flat != uint16_t(DetailEncoding::kOffset + 0.5)), 0);
  const nlohmann::json j = read_json(dir.path() / "detail" / "detail.json");
  EXPECT_EQ(j.at("maps"), 3);
  EXPECT_EQ(j.at("flat_maps"), 1);
  EXPECT_NEAR(j.at("displacement_mm").at("rms").get<double>(),
              10.0 * std::sqrt(wrinkles.squaredNorm() / wrinkles.size()), 1e-5);
}

// The encoding's ends: zero at the middle, the range at the ends, beyond it clamped.
TEST(DetailMaps, TheEncodingSpansTheRangeAndClampsBeyondIt) {
  const DetailEncoding e;
  EXPECT_NEAR(e.decode(e.encode(0.0)), 0.0, e.range_mm / 65535);
  EXPECT_EQ(e.encode(e.range_mm), 65535);
  EXPECT_EQ(e.encode(-e.range_mm), 0);
  EXPECT_EQ(e.encode(10 * e.range_mm), 65535);
  EXPECT_NEAR(e.decode(e.encode(0.1234)), 0.1234, e.range_mm / 65535);
}

// A displacement that does not fit the hierarchy is refused, naming the problem.
TEST(DetailMaps, ADisplacementOfAnotherMeshIsRefused) {
  FACECAP_REQUIRE_MODEL(model);
  const MeshHierarchy h = frontal_hierarchy(*model);
  TempDir dir;
  DetailMaps maps(*model, dir.path(), 64);
  EXPECT_THROW(maps.add(0, h, Eigen::VectorXf::Zero(10)), Error);
}

}  // namespace facecap
