// TrackMeshes (track --meshes, --point-cache): a PLY frame is the OBJ frame's
// surface with each vertex's normal, and with --refine its albedo as the
// vertex colour; a point cache holds every frame's mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <vector>

#include "facecap/core/mesh.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"
#include "facecap/model/obj_reader.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/track_job.hpp"
#include "io/ply_reader.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;
using test::Ply;
using test::read_file;

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
TEST(TrackMeshes, APlyFrameIsTheObjFrameWithNormals) {
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
TEST(TrackMeshes, ARefinedPlyCarriesTheAlbedoAsVertexColours) {
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
    // OBJ's UV origin is the image's bottom-left; texel x's centre at u = (x + 0.5) / N.
    const int x = int(std::floor(ply.vertex.at("s")[i] * albedo.cols));
    const int y = int(std::floor((1.0 - ply.vertex.at("t")[i]) * albedo.rows));
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

namespace {

// A PC2 file read back: its header and every sample's points.
struct Pc2 {
  int points = 0, samples = 0;
  float start = 0, sampling = 0;
  std::vector<std::vector<float>> frames;  // x y z of each point in turn

  Eigen::Vector3d point(int sample, size_t i) const {
    const float* p = frames[size_t(sample)].data() + 3 * i;
    return {p[0], p[1], p[2]};
  }

  static Pc2 read(const fs::path& file) {
    const std::string bytes = read_file(file);
    Pc2 c;
    if (bytes.size() < 32 || bytes.compare(0, 12, std::string("POINTCACHE2\0", 12)) != 0)
      throw std::runtime_error("not a PC2 file");
    std::memcpy(&c.points, bytes.data() + 16, 4);
    std::memcpy(&c.start, bytes.data() + 20, 4);
    std::memcpy(&c.sampling, bytes.data() + 24, 4);
    std::memcpy(&c.samples, bytes.data() + 28, 4);
    if (bytes.size() != 32 + size_t(c.points) * size_t(c.samples) * 12) throw std::runtime_error("PC2 size");
    for (int s = 0; s < c.samples; ++s) {
      std::vector<float> points(3 * size_t(c.points));
      std::memcpy(points.data(), bytes.data() + 32 + size_t(s) * size_t(c.points) * 12, size_t(c.points) * 12);
      c.frames.push_back(std::move(points));
    }
    return c;
  }
};

// A folder of talking_webcam's first 36 frames with frames 0, 1 and 31 blank.
void frames_with_blanks(const fs::path& video, const fs::path& folder) {
  auto source = open_input(video.string());
  Frame f;
  for (int i = 0; i < 36 && source->read(f); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "f%03d.png", i);
    const bool blank = i == 0 || i == 1 || i == 31;
    write_image((folder / name).string(),
                blank ? cv::Mat(f.image.size(), f.image.type(), cv::Scalar::all(60)) : f.image);
  }
}

}  // namespace

// A refined OBJ names the albedo as its texture, through a material library
// beside it (meshes/face.mtl; face.mtl beside the point cache's rest mesh),
// which every frame names. A run without --refine has no albedo: it names
// none, and the earlier run's libraries go.
TEST(TrackMeshes, ARefinedObjNamesTheAlbedoThroughItsMaterial) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  TrackOptions o = mesh_options(20, MeshFormat::kObj);
  o.refine = true;
  o.point_cache = true;
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  ASSERT_EQ(s.refined_frames, 20 - s.capture.lost);
  ASSERT_TRUE(fs::exists(dir.path() / "albedo.png"));
  const std::vector<std::string> library = test::read_lines(dir.path() / "meshes" / "face.mtl");
  EXPECT_NE(std::find(library.begin(), library.end(), "newmtl face"), library.end());
  EXPECT_NE(std::find(library.begin(), library.end(), "map_Kd ../albedo.png"), library.end());
  const std::vector<std::string> rest_library = test::read_lines(dir.path() / "face.mtl");
  EXPECT_NE(std::find(rest_library.begin(), rest_library.end(), "map_Kd albedo.png"), rest_library.end());
  for (const fs::path& obj : {dir.path() / "meshes" / "frame_000019.obj", dir.path() / "face_rest.obj"}) {
    const std::vector<std::string> lines = test::read_lines(obj);
    EXPECT_NE(std::find(lines.begin(), lines.end(), "mtllib face.mtl"), lines.end()) << obj;
    EXPECT_NE(std::find(lines.begin(), lines.end(), "usemtl face"), lines.end()) << obj;
  }

  o.refine = false;
  run_track(*model, video.string(), dir.path(), o);
  EXPECT_FALSE(fs::exists(dir.path() / "meshes" / "face.mtl"));
  EXPECT_FALSE(fs::exists(dir.path() / "face.mtl"));
  EXPECT_EQ(read_file(dir.path() / "meshes" / "frame_000019.obj").find("mtllib"), std::string::npos);
}

// --point-cache: one sample per frame from the shot's first, each the mesh
// --meshes writes for that frame, to the float; frames without a face hold
// the nearest earlier mesh (the first face's before it), and the rest mesh is
// the first face's frame mesh.
TEST(TrackMeshes, APointCacheHoldsEveryFramesMesh) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const fs::path frames = dir.path() / "frames", out = dir.path() / "out";
  fs::create_directories(frames);
  frames_with_blanks(video, frames);
  TrackOptions o = mesh_options(0, MeshFormat::kPly);
  o.point_cache = true;
  const TrackSummary s = run_track(*model, frames.string(), out, o);
  ASSERT_EQ(s.capture.lost, 3);
  EXPECT_EQ(s.point_cache_files, (std::vector<fs::path>{out / "face.pc2", out / "face_rest.ply"}));
  const Pc2 cache = Pc2::read(out / "face.pc2");
  EXPECT_EQ(cache.points, regions::kFace.num_vertices());
  EXPECT_EQ(cache.start, 0.0f);
  EXPECT_EQ(cache.sampling, 1.0f);
  ASSERT_EQ(cache.samples, 36);
  EXPECT_EQ(read_file(out / "face_rest.ply"), read_file(out / "meshes" / "frame_000002.ply"));
  for (int k = 0; k < 36; ++k) {
    const int shown = k < 2 ? 2 : k == 31 ? 30 : k;
    const Ply mesh =
        Ply::read(out / "meshes" /
                  ("frame_" + std::string(6 - std::to_string(shown).size(), '0') + std::to_string(shown) + ".ply"));
    for (size_t i = 0; i < mesh.vertices(); i += 97)
      ASSERT_EQ(cache.point(k, i), mesh.point(i)) << "sample " << k << " vertex " << i;
  }
}

}  // namespace facecap
