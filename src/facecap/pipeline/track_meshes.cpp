#include "facecap/pipeline/track_meshes.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "facecap/core/version.hpp"
#include "facecap/io/mesh_writer.hpp"
#include "facecap/io/ply_writer.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/frame_files.hpp"
#include "facecap/pipeline/shot_animations.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPointCache = "face.pc2";
// The OBJs' material (their texture: texture.png, else the albedo) and its library's name.
constexpr const char* kMaterial = "face";
constexpr const char* kMaterialLibrary = "face.mtl";

// Camera-space points back to the model frame: X = F R^T (Y - t).
Positions to_model(const Positions& camera_points, const HeadPose& pose) {
  const Mat3f rf = pose.model_to_camera_rotation().cast<float>();
  return rf.transpose() * (camera_points.colwise() - pose.translation.cast<float>());
}

}  // namespace

TrackMeshes::TrackMeshes(const FaceModel& model, const fs::path& dir, const TrackOptions& options)
    : model_(model), dir_(dir), options_(options), face_polygons_(model.region_polygons(regions::kFace)) {
  face_mesh_ = model.region_mesh(regions::kFace);
  if (options.meshes) fs::create_directories(dir / "meshes");
}

void TrackMeshes::add(const CapturedFrame& f, int shot_first_frame, const Refinement* ref, const Positions& coarse) {
  if (options_.meshes) write_mesh(f, ref, coarse);
  if (options_.point_cache) append_to_point_cache(f, shot_first_frame, ref, coarse);
}

void TrackMeshes::end_shot(const fs::path* texture_file) {
  if (material_) {
    for (const fs::path& dir : material_->dirs) {
      const fs::path file = dir / material_->name;
      const std::string texture = texture_file != nullptr ? fs::relative(*texture_file, dir).generic_string() : "";
      write_mtl(staged_.stage(file), kMaterial, texture,
                "facecap " + std::string(kFacecapVersion) + ": the meshes' texture (ICT UV layout)");
      material_files_.push_back(file);
    }
    material_.reset();
  }
  if (!point_cache_) return;
  point_cache_->writer->finish();
  point_cache_.reset();
}

void TrackMeshes::finish() {
  end_shot();
  staged_.commit();
  // An earlier run's libraries that this run did not write.
  for (const fs::path& dir : {dir_ / "meshes", dir_}) {
    if (dir == dir_ ? !options_.point_cache : !options_.meshes) continue;
    std::vector<fs::path> written;
    for (const fs::path& file : material_files_)
      if (file.parent_path() == dir) written.push_back(file);
    remove_other_shot_files(dir / kMaterialLibrary, written, /*remove_first_when_none=*/true);
  }
  if (options_.point_cache) {
    remove_other_shot_files(dir_ / kPointCache, point_cache_files_, /*remove_first_when_none=*/true);
    remove_other_shot_files(dir_ / point_cache_rest_name(), point_cache_rest_files_, /*remove_first_when_none=*/true);
  }
  if (options_.meshes) remove_unwritten_frame_files(dir_ / "meshes", {"obj", "ply"}, meshes_written_);
}

std::vector<fs::path> TrackMeshes::point_cache_files() const {
  std::vector<fs::path> files;
  for (size_t k = 0; k < point_cache_files_.size(); ++k) {
    files.push_back(point_cache_files_[k]);
    files.push_back(point_cache_rest_files_[k]);
  }
  return files;
}

void TrackMeshes::write_mesh(const CapturedFrame& f, const Refinement* ref, const Positions& coarse) {
  const std::string name = frame_file_name(f.index, mesh_extension());
  meshes_written_.insert(name);
  write_frame_mesh(dir_ / "meshes" / name, dir_ / "meshes", f, ref, coarse);
  ++meshes_;
}

const char* TrackMeshes::mesh_extension() const { return options_.mesh_format == MeshFormat::kPly ? "ply" : "obj"; }

Positions TrackMeshes::mesh_positions(const CapturedFrame& f, const Refinement* ref, const Positions& coarse) const {
  const Positions& camera_points = refined(ref) ? ref->positions : coarse;
  return options_.mesh_space == MeshSpace::kCamera ? camera_points : to_model(camera_points, f.fit.pose);
}

std::string TrackMeshes::material_library(const CapturedFrame& f, const fs::path& dir) {
  if (!material_) material_ = ShotMaterial{shot_file(kMaterialLibrary, f.shot, material_shots_++ == 0).string(), {}};
  if (std::find(material_->dirs.begin(), material_->dirs.end(), dir) == material_->dirs.end())
    material_->dirs.push_back(dir);
  return material_->name;
}

void TrackMeshes::write_frame_mesh(const fs::path& file, const fs::path& dir, const CapturedFrame& f,
                                   const Refinement* ref, const Positions& coarse) {
  const bool ply = options_.mesh_format == MeshFormat::kPly;
  const bool camera_space = options_.mesh_space == MeshSpace::kCamera;
  std::string comment = "facecap " + std::string(kFacecapVersion) + " frame " + std::to_string(f.index) +
                        (camera_space ? "\ncamera space (x right, y down, z forward), cm"
                                      : "\nICT model space (y up, z out of the face), cm");
  const Positions out = mesh_positions(f, ref, coarse);
  if (refined(ref)) {
    // The refined finest level, with UVs prolonged through the hierarchy.
    const MeshHierarchy& h = refiner_->hierarchy();
    const int finest = h.num_levels() - 1;
    if (!refined_uvs_) {
      refined_uvs_ = level_uv_mesh(h, finest, coarse_uvs()).uvs;
      for (const Triangle& t : h.level(finest).triangles) {
        Polygon p;
        for (int k = 0; k < 3; ++k) p.v[k] = p.uv[k] = t[k];
        refined_polygons_.push_back(p);
      }
    }
    comment += "\nrefined (finest level)";
    if (ply) {
      const Positions normals =
          camera_space ? ref->normals
                       : Positions(f.fit.pose.model_to_camera_rotation().cast<float>().transpose() * ref->normals);
      write_ply(file, {.positions = &out,
                       .polygons = &refined_polygons_,
                       .normals = &normals,
                       .colours = &ref->albedo,
                       .uvs = &*refined_uvs_,
                       .comment = comment + "\nvertex colours: the albedo (RGB, as albedo.png)"});
    } else {
      write_obj(file, {.positions = &out,
                       .polygons = &refined_polygons_,
                       .uvs = &*refined_uvs_,
                       .comment = comment,
                       .material_library = material_library(f, dir),
                       .material = kMaterial});
    }
  } else if (ply) {
    const Positions normals = vertex_normals(out, face_mesh_.triangles);
    write_ply(file, {.positions = &out,
                     .polygons = &face_polygons_,
                     .normals = &normals,
                     .colours = nullptr,  // no albedo without --refine
                     .uvs = &coarse_uvs(),
                     .comment = comment});
  } else {
    // With --texture, the coarse face has a texture too.
    write_obj(file, {.positions = &out,
                     .polygons = &face_polygons_,
                     .uvs = &model_.uvs,
                     .comment = comment,
                     .material_library = options_.texture ? material_library(f, dir) : "",
                     .material = options_.texture ? kMaterial : ""});
  }
}

std::string TrackMeshes::point_cache_rest_name() const { return std::string("face_rest.") + mesh_extension(); }

void TrackMeshes::append_to_point_cache(const CapturedFrame& f, int shot_first_frame, const Refinement* ref,
                                        const Positions& coarse) {
  const Positions points = mesh_positions(f, ref, coarse);
  if (!point_cache_) {
    if (options_.refine && !refined(ref)) return;  // the cache holds the refined level: wait for it
    const bool first = point_cache_files_.empty();
    const fs::path file = shot_file(dir_ / kPointCache, f.shot, first);
    const fs::path rest = shot_file(dir_ / point_cache_rest_name(), f.shot, first);
    point_cache_files_.push_back(file);
    point_cache_rest_files_.push_back(rest);
    write_frame_mesh(staged_.stage(rest), dir_, f, ref, coarse);
    point_cache_.emplace(OpenPointCache{
        std::make_unique<PointCacheWriter>(staged_.stage(file), int(points.cols()), float(shot_first_frame)), points,
        shot_first_frame});
  }
  OpenPointCache& cache = *point_cache_;
  if (points.cols() != cache.last.cols()) return;  // not the cache's level: held as a frame without a face
  for (; cache.next_frame < f.index; ++cache.next_frame) cache.writer->append(cache.last);
  cache.writer->append(points);
  cache.last = points;
  cache.next_frame = f.index + 1;
}

const std::vector<Vec2f>& TrackMeshes::coarse_uvs() {
  if (!coarse_uvs_) coarse_uvs_ = per_vertex_uvs(face_mesh_);
  return *coarse_uvs_;
}

}  // namespace facecap
