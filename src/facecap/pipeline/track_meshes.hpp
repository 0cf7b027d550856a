#pragma once
// The meshes `facecap track` writes (track_job.hpp): one a frame with a face
// (--meshes: DIR/meshes/frame_NNNNNN.obj, or .ply with --mesh-format ply:
// io/mesh_writer.hpp, io/ply_writer.hpp; OBJs name their texture,
// texture.png or the refinement's albedo.png, through DIR/meshes/face.mtl)
// and one point cache a shot
// (--point-cache: DIR/face.pc2 with the mesh it animates, DIR/face_rest.obj
// or .ply: io/point_cache.hpp; later shots' face_shot<N>.pc2 and
// face_rest_shot<N>). A frame's mesh is the refined finest level where the
// frame was refined, else the coarse face region, in --mesh-space.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "facecap/core/atomic_file.hpp"
#include "facecap/io/point_cache.hpp"
#include "facecap/pipeline/track_job.hpp"

namespace facecap {

class TrackMeshes {
 public:
  TrackMeshes(const FaceModel& model, const std::filesystem::path& dir, const TrackOptions& options);

  // The refinement whose levels the refined frames come from (none: coarse only).
  void set_refiner(const Refiner* refiner) { refiner_ = refiner; }
  // A frame with a face: its mesh, and its place in its shot's point cache.
  // `shot_first_frame`: the index of the first frame of its shot.
  // `coarse`: the coarse face region in camera space.
  void add(const CapturedFrame& f, int shot_first_frame, const Refinement* ref, const Positions& coarse);
  // The current shot's point cache complete, and the material library of
  // its OBJ meshes written, naming `texture` (the shot's texture.png or
  // albedo.png; null: none) as their texture (they appear with finish()).
  void end_shot(const std::filesystem::path* texture = nullptr);
  // Every shot's cache and rest mesh renamed into place, and an earlier
  // run's meshes and caches that this run did not write removed.
  void finish();

  int meshes_written() const { return meshes_; }
  // --point-cache: each shot's cache, then its rest mesh.
  std::vector<std::filesystem::path> point_cache_files() const;

 private:
  void write_mesh(const CapturedFrame& f, const Refinement* ref, const Positions& coarse);
  const char* mesh_extension() const;
  // Whether the frame's mesh is the refined finest level (else the coarse face region).
  bool refined(const Refinement* ref) const { return ref != nullptr && refiner_ != nullptr; }
  // The points of the frame's mesh, as --meshes writes them: in --mesh-space.
  Positions mesh_positions(const CapturedFrame& f, const Refinement* ref, const Positions& coarse) const;
  // `file` is written now (maybe under a staged name) and will be in `dir`.
  void write_frame_mesh(const std::filesystem::path& file, const std::filesystem::path& dir, const CapturedFrame& f,
                        const Refinement* ref, const Positions& coarse);
  // The material library an OBJ frame in `dir` names, refined or with
  // --texture (written at the
  // end of its shot, beside it: DIR/meshes/face.mtl, DIR/face.mtl for the
  // point cache's rest mesh; face_shot<N>.mtl for later shots).
  std::string material_library(const CapturedFrame& f, const std::filesystem::path& dir);
  std::string point_cache_rest_name() const;
  // The frame's mesh positions appended to its shot's cache, which opens at
  // the shot's first frame with a face (its rest mesh that frame's mesh).
  // The shot's frames without a face before it, and between faces, hold the
  // nearest earlier positions (the first ones before the first face), so
  // that sample k is the shot's frame k; a refined frame without its
  // refinement counts as one without a face.
  void append_to_point_cache(const CapturedFrame& f, int shot_first_frame, const Refinement* ref,
                             const Positions& coarse);
  // One UV a face-region vertex (its corners share one on the face region:
  // the layout's seams lie outside it).
  const std::vector<Vec2f>& coarse_uvs();

  const FaceModel& model_;
  std::filesystem::path dir_;
  const TrackOptions& options_;  // the track job's, which outlives this
  std::vector<Polygon> face_polygons_;
  TriangleMesh face_mesh_;
  const Refiner* refiner_ = nullptr;
  std::optional<std::vector<Vec2f>> coarse_uvs_, refined_uvs_;
  std::vector<Polygon> refined_polygons_;
  int meshes_ = 0;
  std::unordered_set<std::string> meshes_written_;  // their file names
  struct OpenPointCache {
    std::unique_ptr<PointCacheWriter> writer;
    Positions last;  // the last sample
    int next_frame = 0;
  };
  std::optional<OpenPointCache> point_cache_;  // the current shot's
  std::vector<std::filesystem::path> point_cache_files_, point_cache_rest_files_;
  // Each shot's cache, rest mesh and material libraries, in place when the capture completes.
  StagedFiles staged_;
  // The current shot's material library: its file name and the folders
  // whose OBJs name it.
  struct ShotMaterial {
    std::string name;
    std::vector<std::filesystem::path> dirs;
  };
  std::optional<ShotMaterial> material_;
  int material_shots_ = 0;                             // shots given a material library
  std::vector<std::filesystem::path> material_files_;  // every library written
};

}  // namespace facecap
