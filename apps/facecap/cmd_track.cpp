#include <csignal>
#include <cstdio>

#include "commands.hpp"
#include "facecap/core/error.hpp"
#include "facecap/io/udp_sender.hpp"
#include "facecap/pipeline/track_each_face.hpp"
#include "facecap/pipeline/track_each_image.hpp"
#include "facecap/pipeline/track_job.hpp"

namespace facecap::cli {

namespace {

// The closing notes of one capture: frames that could not be read, the
// refinement's timing, the Live Link stream.
void report_notes(const TrackSummary& s, const std::string& input, bool refine, const char* indent) {
  if (const std::string note = damaged_input_note(s.capture, input); !note.empty())
    std::fprintf(stderr, "facecap: %s\n", note.c_str());
  if (refine)
    std::fprintf(stderr, "%srefinement: %d frames, %.1f ms per frame on its own thread\n", indent, s.refined_frames,
                 s.refine_ms / std::max(1, s.refined_frames));
  if (!s.livelink_address.empty()) {
    std::fprintf(stderr, "%sLive Link: %d frame(s) sent to %s\n", indent, s.livelink_sent, s.livelink_address.c_str());
    if (!s.livelink_error.empty())
      std::fprintf(stderr, "facecap: %d frame(s) could not be sent to %s (%s)\n", s.capture.frames - s.livelink_sent,
                   s.livelink_address.c_str(), s.livelink_error.c_str());
  }
}

// The closing lines of one capture on stderr: per-stage timings, shots, faces
// in view, unreadable frames, the refinement.
void report_track(const TrackSummary& s, const std::string& input, bool refine, bool identity_given) {
  const StageTimings& t = s.capture.timings;
  const double n = std::max(1, t.frames);
  std::fprintf(stderr,
               "frames %d, lost %d (%d turned down by the fit), redetected %d | per frame: decode %.2f ms (own "
               "thread), detect %.2f ms, landmarks %.2f ms, fit %.2f ms and gaze %.2f ms (beside the next frame's "
               "detection and landmarks) | identity solve %.0f ms, setup %.0f ms | %.1f fps\n"
               "%s (%.1f px) from %d frame(s); gaze in %d frames\n",
               s.capture.frames, s.capture.lost, s.capture.rejected, s.capture.redetected, t.decode_ms / n,
               t.detect_ms / n, t.landmarks_ms / n, t.fit_ms / n, t.iris_ms / n, t.identity_ms, t.setup_ms, t.fps(),
               identity_given ? "identity given; focal" : "identity and focal", s.capture.identity.focal,
               s.capture.identity.frames_used, s.gaze_frames);
  if (s.capture.cuts > 0) {
    std::string starts;
    for (const CaptureSummary::Shot& shot : s.capture.shots)
      starts += (starts.empty() ? "" : ", ") + std::to_string(shot.first_frame);
    std::fprintf(stderr,
                 "facecap: %d shot cut(s); identity and focal solved again for each shot with a face (starting at "
                 "frames %s; identity.json \"shots\", frames.jsonl \"shot\")\n",
                 s.capture.cuts, starts.c_str());
  }
  if (s.capture.most_faces > 1) {
    std::fprintf(stderr,
                 "facecap: up to %d faces in view; one is tracked per run (--face chooses which: largest, left, "
                 "right or X,Y)\n",
                 s.capture.most_faces);
  }
  report_notes(s, input, refine, "");
}

// --all-faces: one line per face, then the shared pass's timings.
void report_face(const FoundFace& face, const TrackSummary& s, const std::string& input, bool refine) {
  const StageTimings& t = s.capture.timings;
  const double n = std::max(1, t.frames);
  std::fprintf(stderr,
               "face %d (from frame %d): %s | frames %d, lost %d | per frame: detect %.2f ms, landmarks %.2f ms, fit "
               "%.2f ms, gaze %.2f ms | identity solve %.0f ms, focal %.1f px\n",
               face.index, face.first_frame, s.output_dir.string().c_str(), s.capture.frames, s.capture.lost,
               t.detect_ms / n, t.landmarks_ms / n, t.fit_ms / n, t.iris_ms / n, t.identity_ms,
               s.capture.identity.focal);
  report_notes(s, input, refine, "  ");
}

void report_all_faces(const AllFacesSummary& all) {
  const StageTimings& t = all.timings;
  const double n = std::max(1, t.frames);
  std::fprintf(stderr,
               "%zu face(s) in %d frames, one decoding pass: decode %.2f ms per frame (own thread), searches for "
               "faces %.2f ms per frame | setup %.0f ms | %.1f fps for all faces\n",
               all.faces.size(), t.frames, t.decode_ms / n, t.detect_ms / n, t.setup_ms, t.fps());
  if (all.cuts > 0) std::fprintf(stderr, "facecap: %d shot cut(s); each face's identity is solved again\n", all.cuts);
  report_uncaptured_faces(all, "not captured");
  report_damaged_input(all.damage, "the input");
}

// The files a capture wrote, one per line.
void print_track_files(const TrackSummary& s, FILE* out, const TrackOptions& options) {
  std::fprintf(out, "%s\n", (s.output_dir / "frames.csv").string().c_str());
  if (options.landmarks_csv) std::fprintf(out, "%s\n", (s.output_dir / "landmarks.csv").string().c_str());
  if (options.action_units) std::fprintf(out, "%s\n", (s.output_dir / "action_units.csv").string().c_str());
  if (options.aligned_faces) std::fprintf(out, "%s\n", (s.output_dir / "aligned").string().c_str());
  if (options.detail_maps) std::fprintf(out, "%s\n", (s.output_dir / "detail").string().c_str());
  if (options.uv_pass) std::fprintf(out, "%s\n", (s.output_dir / "uv").string().c_str());
  if (!s.face_matte.empty()) std::fprintf(out, "%s\n", s.face_matte.string().c_str());
  if (options.livelink) std::fprintf(out, "%s\n", (s.output_dir / "livelink_face.csv").string().c_str());
  for (const std::filesystem::path& file : s.chan_files) std::fprintf(out, "%s\n", file.string().c_str());
  for (const std::filesystem::path& file : s.animation_files) std::fprintf(out, "%s\n", file.string().c_str());
  for (const std::filesystem::path& file : s.point_cache_files) std::fprintf(out, "%s\n", file.string().c_str());
}

}  // namespace

void register_track(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand(
      "track",
      "Capture head pose, focal length, identity and 53 expression weights per frame: DIR/frames.csv, "
      "DIR/frames.jsonl, DIR/identity.json, and optionally meshes, an animated glTF and an overlay video");
  struct Args {
    std::string input, out, mesh_space = "model", mesh_format = "obj", subject = "facecap";
    bool stream = false, all_faces = false, each_image = false;
    TrackOptions options;
    AllFacesOptions all;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUT", a->input, "Video file, image, folder of images, or cam:N")->required();
  cmd->add_option("-o,--output", a->out, "Output folder")->required();
  CLI::Option* meshes = cmd->add_flag("--meshes", a->options.meshes,
                                      "Write one mesh per tracked frame (face region, with UVs) to DIR/meshes");
  cmd->add_option("--mesh-space", a->mesh_space, "Coordinates of the meshes: model (y up) or camera (OpenCV)")
      ->check(CLI::IsMember({"model", "camera"}))
      ->capture_default_str();
  CLI::Option* point_cache = cmd->add_flag(
      "--point-cache", a->options.point_cache,
      "Write DIR/face.pc2: the meshes --meshes would write (with --refine the refined ones), every frame's in one "
      "PC2 point cache, and DIR/face_rest.obj (or .ply), the mesh it animates: in Blender, import the mesh and add "
      "a Mesh Cache modifier with the .pc2 (Frame Start: the header's start frame, 0 for a video's first shot); "
      "frames without a face hold the last positions. One pair per shot (face_shot<N>.pc2 after the first)");
  CLI::Option* mesh_format =
      cmd->add_option(
             "--mesh-format", a->mesh_format,
             "File format of the meshes: obj (text: positions, UVs, quads) or ply (binary, about half the size, "
             "with each vertex's normal too, and with --refine its albedo as the vertex colour, which MeshLab, "
             "CloudCompare, Open3D and Blender show)")
          ->check(CLI::IsMember({"obj", "ply"}))
          ->capture_default_str();
  CLI::Option* overlay =
      cmd->add_flag("--overlay", a->options.overlay,
                    "Write DIR/overlay.mp4: landmarks and mesh over the input, with its audio (with --refine also "
                    "DIR/shaded.mp4 and DIR/heatmap.mp4)");
  add_encoding_options(*cmd, a->options.encoding, "the overlay videos", overlay);
  cmd->add_flag("--gltf", a->options.gltf,
                "Write DIR/animation.glb: the face with its 53 blend shapes as morph targets, head pose and weights "
                "keyed per frame, and the fitted camera, for Blender, three.js and other glTF tools (with --refine, "
                "textured with the albedo). A video that cuts gets one per shot: DIR/animation_shot<N>.glb after the "
                "first. Also DIR/face_matte.png, in the same UV layout: 255 on the face itself (brows to chin, cheek "
                "to cheek), 0 on the region's scalp, ears and neck, feathered between, so that a render over the "
                "footage leaves the person's own hair, ears and neck in view (blender/import_facecap.py uses it)");
  CLI::Option* texture =
      cmd->add_flag("--texture", a->options.texture,
                    "Write DIR/texture.png: the face's skin over its first --texture-frames frames (a photo: the "
                    "photo), unshaded by their lighting into the ICT UV layout, at the image's resolution where "
                    "--refine's albedo.png is one colour a vertex. The --meshes OBJs (through meshes/face.mtl) and "
                    "the --gltf animation take it as their texture. One per shot (texture_shot<N>.png)");
  cmd->add_option("--texture-frames", a->options.texture_frames,
                  "--texture: how many of a shot's first frames with a face it is gathered over (more see more of "
                  "the face as the head turns)")
      ->check(CLI::Range(1, 1000))
      ->needs(texture)
      ->capture_default_str();
  cmd->add_flag("--landmarks-csv", a->options.landmarks_csv,
                "Write DIR/landmarks.csv: each frame's 68 landmarks in OpenFace's columns: the detector's (x_0 ... "
                "y_67, pixels), the fitted model's projected (fit_x_0 ... fit_y_67) and the fitted model's in camera "
                "space (X_0 ... Z_67, millimetres, x right, y down, z forward)");
  cmd->add_flag("--action-units", a->options.action_units,
                "Write DIR/action_units.csv: each frame's FACS action units in OpenFace's columns, intensity AU01_r "
                "... AU45_r (0-5) and presence AU01_c ... AU45_c (0 or 1, from intensity 1), read off the fitted "
                "expression weights (a weight of 1 is intensity 5); ICT has no shape for AU23 and AU25, which are "
                "left out");
  CLI::Option* aligned = cmd->add_flag(
      "--aligned-faces", a->options.aligned_faces,
      "Write DIR/aligned/frame_NNNNNN.png: each tracked frame's face cropped upright, its eyes, nose tip and mouth "
      "corners moved by a similarity onto the 5-point template of ArcFace (InsightFace's recognition models), the "
      "input that face recognition and expression networks take");
  cmd->add_option("--aligned-size", a->options.aligned_face_size,
                  "--aligned-faces: the crops' width and height in pixels (the template scaled from its 112)")
      ->check(CLI::Range(32, 1024))
      ->needs(aligned)
      ->capture_default_str();
  cmd->add_flag("--uv-pass", a->options.uv_pass,
                "Write DIR/uv/frame_NNNNNN.png: each frame's UV pass (an ST map) at the input's size, 16-bit RGBA: red "
                "u and green v of the face's surface point each pixel shows, in the ICT UV layout of albedo.png and "
                "texture.png, alpha where the face region covers the pixel (with --refine, the refined surface's); "
                "an empty pass for a frame without a face. Nuke's STMap node (or another compositor's UV map) puts a "
                "texture painted in that layout onto the face in every frame; DIR/face_matte.png put through it is "
                "the matte of the face itself");
  CLI::Option* chan = cmd->add_flag(
      "--chan", a->options.chan,
      "Write DIR/head.chan and DIR/camera.chan: each tracked frame's head pose and the camera's vertical field of "
      "view as Nuke .chan files (frame tx ty tz rx ry rz [vfov]; centimetres, degrees, rotation order ZXY, Nuke's "
      "y-up space with the camera at the origin looking down -z), for Nuke's Axis and Camera nodes (Import chan "
      "file), Houdini and Blender's Nuke .chan add-on. Put the --meshes (model space, the default) under the head's "
      "Axis and they sit on the face through the camera; give the camera the plate's aspect (e.g. apertures 36 x "
      "20.25 mm for 16:9)");
  cmd->add_option("--chan-first-frame", a->options.chan_first_frame,
                  "--chan: the frame number the input's first frame takes in the .chan files (Nuke numbers a "
                  "movie's frames from 1; an image sequence keeps its own numbers)")
      ->needs(chan)
      ->capture_default_str();
  cmd->add_flag("--livelink", a->options.livelink,
                "Write DIR/livelink_face.csv: the 52 ARKit blend shapes, head rotation and gaze per frame as a Live "
                "Link Face take (Timecode, BlendShapeCount, EyeBlinkLeft ... RightEyeRoll; angles in radians), for "
                "Unreal's Live Link Face importer (MetaHuman) and ARKit rigs in Blender or Maya");
  cmd->add_option_function<std::string>(
         "--livelink-udp",
         [a](const std::string& text) {
           a->options.livelink_stream.emplace();
           a->options.livelink_stream->target = parse_network_target(text, 11111, "--livelink-udp");
         },
         "Also send each frame's Live Link Face values (as --livelink) to HOST[:PORT] (default port 11111) as the "
         "iPhone app's UDP stream does, as it is captured: Unreal's Live Link (a MetaHuman) follows a camera live; a "
         "file's frames go at its own pace. With --all-faces, each face is a subject of its own (NAME_face<k>)")
      ->check([](const std::string& text) {
        try {
          parse_network_target(text, 11111, "");  // CLI11 names the option
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      });
  cmd->add_option("--livelink-subject", a->subject, "--livelink-udp: the Live Link subject name")
      ->needs("--livelink-udp")
      ->capture_default_str();
  CLI::Option* refine =
      cmd->add_flag("--refine", a->options.refine,
                    "Shading-based refinement: per-frame SH lighting, DIR/albedo.png, wrinkle-level meshes");
  CLI::Option* detail_maps = cmd->add_flag(
      "--detail-maps", a->options.detail_maps,
      "Write DIR/detail/frame_NNNNNN.png: each refined frame's wrinkle-level detail (the refinement's displacement "
      "along the tracked surface's normal) as a 16-bit displacement map in the ICT UV layout of albedo.png, and "
      "DIR/detail/detail.json: value / 65535 = 0.5 + mm / 4 (Blender's Displace: UV, midlevel 0.5, strength 0.4 "
      "cm, the image read as non-colour data); a frame without a refined face gets a flat map, so the sequence "
      "has no gaps. blender/import_facecap.py puts them on the --gltf animation");
  detail_maps->needs(refine);
  cmd->add_option("--detail-map-size", a->options.detail_map_size,
                  "--detail-maps: the maps' width and height in texels")
      ->check(CLI::Range(64, 4096))
      ->needs(detail_maps)
      ->capture_default_str();
  add_device_option(*cmd, a->options.refine_options.device);
  cmd->add_option("--focal", a->options.capture.fit.focal_guess,
                  "Focal length in pixels: a starting guess, or the value to keep with --focal-known (0: none given)")
      ->check(number_between(0, 100000));
  cmd->add_flag("--focal-known", a->options.capture.fit.focal_known, "Hold --focal fixed (a calibrated camera)");
  add_frame_range_options(*cmd, a->options.capture);
  const FitCliOptions fit = add_fit_options(*cmd, a->options.capture);
  CLI::Option* identity = add_identity_option(*cmd, a->options.capture.fit.known_identity);
  CLI::Option* all_faces = add_all_faces_options(
      *cmd, a->all_faces, a->all,
      "Track every face the input shows, each into DIR/face_<k> (k in the order found) from the frame it is first "
      "found in, with DIR/faces.json listing them; one decoding pass for all (a face entering later is found within "
      "--search-every frames)");
  all_faces->excludes(fit.face)->excludes(identity);  // one person's face for every face
  CLI::Option* stream =
      cmd->add_flag("--stream", a->stream,
                    "Also print each frame's row (as in frames.jsonl) on stdout as soon as it is done, for a program "
                    "reading the capture live (cam:N; rows start once the identity is solved, after --init-frames "
                    "frames); the closing list of files then goes to stderr");
  stream->excludes("--all-faces");
  cmd->add_flag("--each-image", a->each_image,
                "INPUT is a folder of portraits, each fitted on its own as a photo is (its own identity and focal "
                "length, any size) into DIR/<image name>, with one table of all: DIR/images.csv and "
                "DIR/images.jsonl (a row per image: status, pose, 53 weights, 50 identity weights). Without it a "
                "folder is one camera's frames of one face")
      ->excludes(all_faces)
      ->excludes(stream)
      ->excludes("--livelink-udp")
      ->excludes("--start");
  cmd->callback([a, &global, meshes, point_cache, mesh_format, smooth = fit.smooth_frames] {
    a->options.mesh_space = a->mesh_space == "camera" ? MeshSpace::kCamera : MeshSpace::kModel;
    a->options.mesh_format = a->mesh_format == "ply" ? MeshFormat::kPly : MeshFormat::kObj;
    if (mesh_format->count() > 0 && meshes->count() == 0 && point_cache->count() == 0)
      throw CLI::ValidationError("--mesh-format", "needs --meshes or --point-cache");
    // Live outputs are not held back for smoothing unless asked to be.
    if ((a->stream || a->options.livelink_stream) && smooth->count() == 0) a->options.capture.fit.smooth_frames = 0;
    a->options.capture.fit.check();
    a->options.capture.quiet = global.quiet;
    if (a->options.livelink_stream) {
      if (a->subject.empty()) throw CLI::ValidationError("--livelink-subject", "must not be empty");
      a->options.livelink_stream->subject = a->subject;
    }
    const FaceModel model = load_model(global);
    if (a->stream) {
      // A reader that goes away (`| head`) ends the stream, not the capture.
      std::signal(SIGPIPE, SIG_IGN);
      a->options.on_row = [open = true](const std::string& row) mutable {
        if (!open) return;
        if (std::fwrite(row.data(), 1, row.size(), stdout) != row.size() || std::fputc('\n', stdout) == EOF ||
            std::fflush(stdout) != 0) {
          open = false;
          std::fprintf(stderr, "facecap: stdout was closed; --stream stops, and the files are still written\n");
        }
      };
    }
    if (a->each_image) {
      const EachImageSummary each = run_track_each_image(model, a->input, a->out, a->options);
      if (each.with_face == 0)
        throw Error("no face found in any of the " + std::to_string(each.images) + " image(s) of " + a->input +
                    " (each one's status is in " + each.tables.front().string() + ")");
      std::fprintf(stderr, "images %d: a face fitted in %d, none found in %d, %d could not be read%s%s%s\n",
                   each.images, each.with_face, each.images - each.with_face - each.unreadable, each.unreadable,
                   each.first_error.empty() ? "" : " (the first: ", each.first_error.c_str(),
                   each.first_error.empty() ? "" : ")");
      for (const std::filesystem::path& table : each.tables) std::printf("%s\n", table.string().c_str());
      return;
    }
    if (a->all_faces) {
      const EachFaceSummary each = run_track_each_face(model, a->input, a->out, a->options, a->all);
      for (size_t k = 0; k < each.runs.size(); ++k)
        report_face(each.faces[k], each.runs[k], a->input, a->options.refine);
      report_all_faces(each.capture);
      for (const TrackSummary& s : each.runs) print_track_files(s, stdout, a->options);
      std::printf("%s\n", (std::filesystem::path(a->out) / "faces.json").string().c_str());
      std::printf("%s\n", (std::filesystem::path(a->out) / "faces.png").string().c_str());
      return;
    }
    const TrackSummary s = run_track(model, a->input, a->out, a->options);
    if (s.capture.identity.frames_used == 0) {
      // frames.csv is still written (every frame "lost"), but there is nothing else to give.
      const std::string note = damaged_input_note(s.capture, a->input);
      throw Error("no face found in " + a->input + ": all " + std::to_string(s.capture.frames) +
                  " frame(s) are lost in " + (std::filesystem::path(a->out) / "frames.csv").string() +
                  (note.empty() ? "" : "; " + note));
    }
    report_track(s, a->input, a->options.refine, a->options.capture.fit.known_identity.has_value());
    print_track_files(s, a->stream ? stderr : stdout, a->options);  // with --stream, stdout holds the rows
  });
}

}  // namespace facecap::cli
