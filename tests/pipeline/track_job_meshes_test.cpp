// track --meshes --mesh-format ply: the same surfaces as the OBJs, with each
// vertex's normal, and with --refine its albedo as the vertex colour.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "facecap/core/mesh.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/obj_reader.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/track_job.hpp"
#include "io/ply_reader.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;
using test::Ply;

namespace {

TrackOptions mesh_options(int frames, MeshFormat format) {
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = frames;
  o.meshes = true;
  o.mesh_format = format;
  return o;
}

int files_with_extension(const fs::path& dir, const char* extension) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == extension;
  return n;
}

}  // namespace

// A coarse frame's PLY holds the OBJ's vertices (to the OBJ's 5 decimals),
// faces (quads kept) and UVs, plus normals: unit, and on the face's front
// (model space, z out of the face) pointing forward. An earlier run's OBJs
// are not left to read as part of the PLY sequence.
TEST(TrackJobMeshes, APlyFrameIsTheObjFrameWithNormals) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const fs::path obj_dir = dir.path() / "obj", ply_dir = dir.path() / "ply";
  run_track(*model, video.string(), obj_dir, mesh_options(4, MeshFormat::kObj));
  fs::create_directories(ply_dir / "meshes");
  fs::copy_file(obj_dir / "meshes" / "frame_000001.obj", ply_dir / "meshes" / "frame_000001.obj");
  const TrackSummary s = run_track(*model, video.string(), ply_dir, mesh_options(4, MeshFormat::kPly));
  ASSERT_EQ(s.capture.lost, 0);
  EXPECT_EQ(files_with_extension(ply_dir / "meshes", ".ply"), 4);
  EXPECT_EQ(files_with_extension(ply_dir / "meshes", ".obj"), 0);

  const ObjData obj = read_obj(obj_dir / "meshes" / "frame_000003.obj");
  const Ply ply = Ply::read(ply_dir / "meshes" / "frame_000003.ply");
  EXPECT_EQ(ply.vertex_properties, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "s", "t"}));
  ASSERT_EQ(ply.vertices(), size_t(obj.num_vertices()));
  ASSERT_EQ(ply.vertices(), size_t(regions::kFace.num_vertices()));
  std::vector<bool> uv_checked(ply.vertices(), false);
  for (const Polygon& poly : obj.polygons)
    for (int k = 0; k < poly.size(); ++k) {
      const size_t v = size_t(poly.v[k]);
      if (uv_checked[v]) continue;
      uv_checked[v] = true;
      EXPECT_NEAR(ply.vertex.at("s")[v], obj.uvs[size_t(poly.uv[k])].x(), 1e-6) << v;
      EXPECT_NEAR(ply.vertex.at("t")[v], obj.uvs[size_t(poly.uv[k])].y(), 1e-6) << v;
    }
  ASSERT_EQ(ply.faces.size(), obj.polygons.size());
  for (size_t f = 0; f < ply.faces.size(); ++f) {
    ASSERT_EQ(ply.faces[f].size(), size_t(obj.polygons[f].size())) << f;
    for (size_t k = 0; k < ply.faces[f].size(); ++k) EXPECT_EQ(ply.faces[f][k], obj.polygons[f].v[k]) << f;
  }
  double forward = 0;
  int front = 0;
  for (size_t i = 0; i < ply.vertices(); ++i) {
    const Eigen::Vector3d p = ply.point(i);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], obj.positions[3 * i + size_t(k)], 6e-6) << i;
    const Eigen::Vector3d n = ply.point(i, "nx", "ny", "nz");
    EXPECT_NEAR(n.norm(), 1.0, 1e-5) << i;
    // The forehead, which faces forward: above the brows, within 3 cm of the midline.
    if (std::abs(p.x()) < 3.0 && p.y() > 5.0 && p.z() > 5.0) {
      forward += n.z();
      ++front;
    }
  }
  ASSERT_GT(front, 200);
  EXPECT_GT(forward / front, 0.8);  // 0.90 measured; inward normals would be negative
}

// --refine: the finest level with its albedo as the vertex colours, in RGB
// order: sampled back from albedo.png at each vertex's UV (the nearest
// texel), they agree to a fraction of a level (0.28 measured: at 400x300 the
// hierarchy is one level, whose albedo the PNG bakes).
TEST(TrackJobMeshes, ARefinedPlyCarriesTheAlbedoAsVertexColours) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  TrackOptions o = mesh_options(32, MeshFormat::kPly);
  o.refine = true;
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  ASSERT_EQ(s.refined_frames, 32 - s.capture.lost);
  const Ply ply = Ply::read(dir.path() / "meshes" / "frame_000031.ply");
  EXPECT_EQ(ply.vertex_properties,
            (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "s", "t"}));
  EXPECT_NE(std::find(ply.comments.begin(), ply.comments.end(), "refined (finest level)"), ply.comments.end());
  ASSERT_GE(ply.vertices(), size_t(regions::kFace.num_vertices()));
  const cv::Mat albedo = read_image((dir.path() / "albedo.png").string());  // BGR
  ASSERT_FALSE(albedo.empty());
  double difference = 0, red_over_blue = 0;
  int sampled = 0;
  for (size_t i = 0; i < ply.vertices(); ++i) {
    const Eigen::Vector3d n = ply.point(i, "nx", "ny", "nz");
    EXPECT_NEAR(n.norm(), 1.0, 1e-4) << i;
    // OBJ's UV origin is the image's bottom-left.
    const int x = int(ply.vertex.at("s")[i] * (albedo.cols - 1) + 0.5);
    const int y = int((1.0 - ply.vertex.at("t")[i]) * (albedo.rows - 1) + 0.5);
    if (x < 0 || y < 0 || x >= albedo.cols || y >= albedo.rows) continue;
    const cv::Vec3b bgr = albedo.at<cv::Vec3b>(y, x);
    if (bgr == cv::Vec3b(0, 0, 0)) continue;  // a texel no triangle covers
    const Eigen::Vector3d rgb = ply.point(i, "red", "green", "blue");
    difference += (rgb - Eigen::Vector3d(bgr[2], bgr[1], bgr[0])).cwiseAbs().mean();
    red_over_blue += rgb.x() - rgb.z();
    ++sampled;
  }
  ASSERT_GT(sampled, regions::kFace.num_vertices() / 2);
  EXPECT_LT(difference / sampled, 1.0);
  EXPECT_GT(red_over_blue / sampled, 40.0);  // 89 measured: skin, red far above blue; swapped channels fail
}

}  // namespace facecap
