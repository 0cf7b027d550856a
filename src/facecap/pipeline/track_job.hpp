#pragma once
// `facecap track INPUT -o DIR`: coarse capture of an input with per-frame
// results in files that spreadsheets, animation tools and scripts read:
//   DIR/frames.csv     one row per frame: index, time, status, pose, focal,
//                      the 53 weights under their ARKit names
//   DIR/frames.jsonl   the same per frame, plus the observed and fitted landmarks
//   DIR/identity.json  identity weights, focal length, image size, conventions
//   DIR/meshes/        (--meshes) one OBJ per tracked frame, face region with
//                      UVs (--mesh-format ply: binary PLY, with normals)
//   DIR/face.pc2       (--point-cache) the same meshes as one point cache, with
//                      DIR/face_rest.obj (.ply), the mesh it animates
//   DIR/texture.png    (--texture) the face's skin from its first frame, in the
//                      ICT UV layout: the meshes' and the glTF's texture
//   DIR/overlay.mp4    (--overlay) landmarks and mesh over the input, its audio kept
//   DIR/animation.glb  (--gltf) the capture as an animated glTF: the face
//                      with the 53 blend shapes as morph targets, head pose
//                      and weights keyed per frame, the fitted camera
//                      (face_animation.hpp); with --refine its albedo texture.
//                      A video that cuts: one per shot (shot_animations.hpp)
//   DIR/landmarks.csv  (--landmarks-csv) each frame's 68 landmarks: the
//                      detector's, the fit's projected and the fit's in
//                      camera space (mm), in OpenFace's columns
//   DIR/action_units.csv (--action-units) each frame's FACS action units,
//                      read off the weights, in OpenFace's AU columns
//                      (action_unit_table.hpp)
//   DIR/aligned/      (--aligned-faces) each tracked frame's face as a
//                      similarity-aligned crop (detect/aligned_face.hpp)
//   DIR/livelink_face.csv (--livelink) the weights, head pose and gaze as a
//                      Live Link Face take, for Unreal (MetaHuman) and
//                      ARKit rigs (io/livelink_csv.hpp)
// With --refine (shading-based refinement, §4.2-4.3) also:
//   lighting columns l0..l8 per frame, DIR/albedo.png (ICT UV layout; one
//   per shot, as the glTF),
//   refined finest-level meshes with --meshes (a PLY's vertex colours the
//   albedo), and with --overlay
//   DIR/shaded.mp4 (the refined geometry shaded) and DIR/heatmap.mp4 (the
//   photometric error, paper Fig. 4.11).
// Every file is written under a temporary name and renamed when complete.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "facecap/io/udp_sender.hpp"
#include "facecap/io/video_encoding.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/refine/refiner.hpp"

namespace facecap {

enum class MeshSpace { kModel, kCamera };
// OBJ: positions, UVs, quads; PLY (binary): also each vertex's normal, and
// with --refine its albedo as the vertex colour (io/ply_writer.hpp).
enum class MeshFormat { kObj, kPly };

struct TrackOptions {
  CaptureOptions capture;
  bool meshes = false;
  MeshSpace mesh_space = MeshSpace::kModel;
  MeshFormat mesh_format = MeshFormat::kObj;
  // DIR/face.pc2: the meshes --meshes would write, as one point cache
  // (io/point_cache.hpp) from the first frame with a face on, and its rest
  // mesh DIR/face_rest.obj (.ply) whose vertex order it follows; one pair per
  // shot (face_shot<N>.pc2 after the first).
  bool point_cache = false;
  // DIR/texture.png: the face's skin over each shot's first
  // `texture_frames` frames with a face, unshaded into the ICT UV layout
  // (photo_face_texture.hpp: FaceTextureGatherer), which the OBJ meshes and
  // the glTF then take as their texture.
  bool texture = false;
  int texture_frames = 30;
  bool overlay = false;
  VideoEncoding encoding;  // the overlay videos'
  bool gltf = false;
  // DIR/landmarks.csv: each frame's detected, fitted and 3D landmarks
  // (landmark_table.hpp: OpenFace's columns)
  bool landmarks_csv = false;
  // DIR/action_units.csv: each frame's FACS action units (action_unit_table.hpp:
  // OpenFace's AU columns)
  bool action_units = false;
  // DIR/aligned/frame_NNNNNN.png: each tracked frame's face, upright and
  // scaled onto ArcFace's 5-point template (detect/aligned_face.hpp), in a
  // square of aligned_face_size pixels.
  bool aligned_faces = false;
  int aligned_face_size = 112;
  bool livelink = false;  // DIR/livelink_face.csv (io/livelink_csv.hpp)
  // Each frame's Live Link Face values also sent as a datagram as the frame
  // is written (io/livelink_packet.hpp: Unreal's Live Link, a MetaHuman).
  struct LiveLinkStream {
    NetworkTarget target;
    std::string subject = "facecap";
    // A file's frames are sent at the file's own pace (the capture waits), so
    // that a rig plays them as fast as they were filmed; a camera's are live.
    bool paced = true;
  };
  std::optional<LiveLinkStream> livelink_stream;
  bool refine = false;
  RefineOptions refine_options;
  // With refine: DIR/detail/frame_NNNNNN.png, each refined frame's
  // displacements as a 16-bit map of detail_map_size texels square in the ICT
  // UV layout, and DIR/detail/detail.json (detail_maps.hpp).
  bool detail_maps = false;
  int detail_map_size = 1024;
  // DIR/uv/frame_NNNNNN.png: each frame's UV pass (an ST map) at the input's
  // size, of the refined surface with refine (uv_passes.hpp).
  bool uv_pass = false;
  // DIR/head.chan and DIR/camera.chan: each tracked frame's head pose and the
  // camera's field of view as Nuke's .chan files (io/nuke_chan.hpp), the
  // input's frame k on line frame k + chan_first_frame (Nuke numbers a
  // movie's frames from 1).
  bool chan = false;
  int chan_first_frame = 1;
  FrameSink on_frame;  // optional: also called with each frame (e.g. to compare against ground truth)
  // Whether the outputs draw on the frames' images (CaptureOptions::keep_images).
  bool needs_images() const { return overlay || refine || texture || aligned_faces; }
  // Optional: each frame's frames.jsonl row (one line of JSON, no newline),
  // in frame order, as soon as it is written (`track --stream`).
  std::function<void(const std::string&)> on_row;
};

struct TrackSummary {
  CaptureSummary capture;
  std::filesystem::path output_dir;
  int meshes_written = 0;
  std::vector<std::filesystem::path> animation_files;    // --gltf: one per shot with a face (shot_animations.hpp)
  std::vector<std::filesystem::path> point_cache_files;  // --point-cache: each shot's cache, then its rest mesh
  int gaze_frames = 0;                                   // frames with an iris found (gaze.hpp)
  int livelink_sent = 0;                                 // TrackOptions::livelink_stream: datagrams sent
  std::string livelink_address;                          // ...to this address, as resolved
  std::string livelink_error;                            // why the first datagram that failed did ("" where none did)
  int refined_frames = 0;
  int detail_maps = 0;               // TrackOptions::detail_maps: the maps written
  int uv_passes = 0;                 // TrackOptions::uv_pass: the passes written
  std::filesystem::path face_matte;  // --gltf or --uv-pass: DIR/face_matte.png (pipeline/face_matte.hpp), if written
  std::vector<std::filesystem::path> chan_files;  // --chan: head.chan and camera.chan, if written
  double refine_ms = 0;                           // total, on the refinement thread
};

TrackSummary run_track(const FaceModel& model, const std::string& input, const std::filesystem::path& output_dir,
                       const TrackOptions& options);
// The same of an input already opened (open_input with
// options.capture.start_seconds), named `input` in the outputs.
TrackSummary run_track(const FaceModel& model, FrameSource& source, const std::string& input,
                       const std::filesystem::path& output_dir, const TrackOptions& options);

// The files of one capture in a folder, as run_track writes them, for a
// capture driven elsewhere (track --all-faces: one per face). `info`: the
// input as the capture sees it. Throws facecap::Error, before writing
// anything, where the folder cannot be written or is one of the input's.
class TrackOutput {
 public:
  TrackOutput(const FaceModel& model, const InputInfo& info, const std::string& input,
              const std::filesystem::path& output_dir, const TrackOptions& options);
  ~TrackOutput();
  TrackOutput(const TrackOutput&) = delete;
  TrackOutput& operator=(const TrackOutput&) = delete;

  // Takes the capture's frames, in order (capture options: keep_images for
  // --overlay and --refine).
  FrameSink sink();
  // Completes the files (renamed into place); throws where no frame came.
  TrackSummary finish(const CaptureSummary& capture);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path output_dir_;
};

}  // namespace facecap
