#include "facecap/pipeline/track_job.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_set>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/version.hpp"
#include "facecap/core/view_frame.hpp"
#include "facecap/detect/aligned_face.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/livelink_csv.hpp"
#include "facecap/io/nuke_chan.hpp"
#include "facecap/model/eyeballs.hpp"
#include "facecap/model/face_shape_cache.hpp"
#include "facecap/pipeline/action_unit_table.hpp"
#include "facecap/pipeline/detail_maps.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/face_matte.hpp"
#include "facecap/pipeline/frame_files.hpp"
#include "facecap/pipeline/landmark_table.hpp"
#include "facecap/pipeline/livelink_streamer.hpp"
#include "facecap/pipeline/photo_face_texture.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/refine_stage.hpp"
#include "facecap/pipeline/shot_animations.hpp"
#include "facecap/pipeline/track_meshes.hpp"
#include "facecap/pipeline/track_videos.hpp"
#include "facecap/pipeline/uv_passes.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// Files of the output folder besides the videos (track_videos.hpp).
constexpr const char* kLiveLinkCsv = "livelink_face.csv";
constexpr const char* kLandmarkTable = "landmarks.csv";
constexpr const char* kActionUnitTable = "action_units.csv";
constexpr const char* kAlignedFaces = "aligned";  // a folder
constexpr const char* kAlbedoImage = "albedo.png";
constexpr const char* kFaceMatteImage = "face_matte.png";
constexpr const char* kTextureImage = "texture.png";
constexpr const char* kHeadChan = "head.chan";
constexpr const char* kCameraChan = "camera.chan";

// A text output written through a temporary file and renamed at the end.
class StagedText {
 public:
  explicit StagedText(const fs::path& path) : file_(path), out_(file_.temp_path()) {
    if (!out_) throw Error("cannot write " + path.string());
  }
  std::ofstream& stream() { return out_; }
  void commit() {
    out_.flush();
    if (!out_) throw Error(write_failure(file_.final_path()));
    out_.close();
    file_.commit();
  }

 private:
  AtomicFile file_;
  std::ofstream out_;
};

nlohmann::json landmarks_json(const Landmarks& lm) {
  nlohmann::json a = nlohmann::json::array();
  for (const Vec2f& p : lm) a.push_back({std::round(p.x() * 100) / 100, std::round(p.y() * 100) / 100});
  return a;
}

// Everything the track job writes, frame by frame, in frame order.
class FrameWriter {
 public:
  FrameWriter(const FaceModel& model, const InputInfo& info, const std::string& input, const fs::path& dir,
              const TrackOptions& options)
      : model_(model),
        info_(info),
        input_(input),
        dir_(dir),
        options_(options),
        csv_(dir / "frames.csv"),
        jsonl_(dir / "frames.jsonl"),
        meshes_(model, dir, options_) {
    std::ofstream& o = csv_.stream();
    o << "frame,time,status,rx,ry,rz,tx,ty,tz,focal,yaw_deg,pitch_deg,roll_deg,landmark_error";
    for (const std::string& name : model.expression_names) o << ',' << name;
    if (options.refine)
      for (int k = 0; k < 9; ++k) o << ",l" << k;
    o << ",gaze_yaw_deg,gaze_pitch_deg,gaze_camera_x,gaze_camera_y,gaze_camera_z,iris_right_x,iris_right_y,iris_left_x,"
         "iris_left_y";
    o << ",shot\n";  // last, so that the columns before keep their places
    if (options.livelink || options.livelink_stream) {
      livelink_face_.emplace(model.expression_names);
      livelink_values_ = livelink_face_->values(Eigen::VectorXf::Zero(model.num_expressions()), {});
    }
    if (options.texture) texture_.emplace(model, options.texture_frames);
    if (options.landmarks_csv) {
      landmarks_.emplace(dir / kLandmarkTable);
      landmarks_->stream() << landmark_table_header() << '\n';
    }
    if (options.action_units) {
      action_units_.emplace(dir / kActionUnitTable);
      action_unit_table_.emplace(model.expression_names);
      action_units_->stream() << action_unit_table_->header() << '\n';
    }
    if (options.aligned_faces) ensure_writable_dir(dir / kAlignedFaces);
    if (options.detail_maps) {
      if (!options.refine) throw Error("detail maps are the refinement's: they need --refine");
      detail_maps_.emplace(model, dir, options.detail_map_size);
    }
    if (options.uv_pass) uv_passes_.emplace(model, dir, cv::Size(info.width, info.height));
    if (options.chan) {
      head_chan_.emplace(dir / kHeadChan);
      camera_chan_.emplace(dir / kCameraChan);
    }
    if (options.livelink) {
      livelink_.emplace(dir / kLiveLinkCsv);
      livelink_csv_.emplace(info.fps);
      livelink_->stream() << livelink_csv_->header() << '\n';
    }
    if (const auto& stream = options.livelink_stream)
      livelink_stream_.emplace(stream->target, stream->subject, info.fps,
                               stream->paced && info.kind != InputKind::kCamera);
    if (options.gltf) {
      animations_.emplace(dir / "animation.glb", [this](const ShotOutput& out, const ShotKeys& shot) {
        const IdentityEstimate& id = shot.identity;
        GltfAnimatedMesh glb = face_animation(model_, id.identity, shot.keys, {id.focal, info_.width, info_.height});
        // The face part's texture: --texture's, else the albedo (--refine).
        glb.primitives.front().base_colour_png = options_.texture ? shot_texture_png_ : shot_albedo_png_;
        glb.animation_name = shot_animation_name(fs::path(input_).stem().string(), shot.shot);
        write_glb(out.write_to, glb);
      });
    }
    if (options.overlay) videos_.emplace(model, info, input, dir, options);
  }

  void write(const CapturedFrame& f, const Refinement* ref, const Positions& coarse, const PinholeCamera& camera) {
    const bool ok = f.status != TrackStatus::kLost;
    if (f.shot != shot_ || shot_first_frame_ < 0) {
      end_shot();
      shot_ = f.shot;
      shot_first_frame_ = f.index;
    }
    shot_has_face_ = shot_has_face_ || ok;
    std::ofstream& o = csv_.stream();
    o << f.index << ',' << csv_number(f.time) << ',' << to_string(f.status);
    nlohmann::json row = {{"frame", f.index}, {"time", f.time}, {"status", to_string(f.status)}, {"shot", f.shot}};
    if (!f.error.empty()) row["error"] = f.error;
    std::optional<Eigen::VectorXd> unit_intensities;  // --action-units: a tracked frame's, for both tables
    if (f.damaged) row["damaged"] = true;
    if (ok) {
      const Vec3d ypr = yaw_pitch_roll_deg(f.fit.pose.rotation_matrix());
      for (int k = 0; k < 3; ++k) o << ',' << csv_number(f.fit.pose.rotation[k]);
      for (int k = 0; k < 3; ++k) o << ',' << csv_number(f.fit.pose.translation[k]);
      o << ',' << csv_number(f.fit.focal);
      for (int k = 0; k < 3; ++k) o << ',' << csv_number(ypr[k]);
      o << ',' << csv_number(f.fit.landmark_error);
      for (Eigen::Index k = 0; k < f.fit.expression.size(); ++k) o << ',' << csv_number(f.fit.expression[k]);
      nlohmann::json weights;
      for (Eigen::Index k = 0; k < f.fit.expression.size(); ++k)
        weights[model_.expression_names[k]] = f.fit.expression[k];
      row["rotation"] = {f.fit.pose.rotation.x(), f.fit.pose.rotation.y(), f.fit.pose.rotation.z()};
      row["translation"] = {f.fit.pose.translation.x(), f.fit.pose.translation.y(), f.fit.pose.translation.z()};
      row["yaw_pitch_roll_deg"] = {ypr.x(), ypr.y(), ypr.z()};
      row["focal"] = f.fit.focal;
      row["landmark_error"] = f.fit.landmark_error;
      row["weights"] = weights;
      row["landmarks"] = landmarks_json(f.fit.observed);
      row["fitted_landmarks"] = landmarks_json(f.fit.fitted);
      if (action_unit_table_) {
        unit_intensities = action_unit_table_->intensities(f.fit.expression);
        row["action_units"] = ActionUnitTable::intensities_json(*unit_intensities);
      }
      if (ref != nullptr) {
        for (int k = 0; k < 9; ++k) o << ',' << csv_number(ref->lighting[k]);
        row["lighting"] = std::vector<double>(ref->lighting.data(), ref->lighting.data() + 9);
      } else if (options_.refine) {
        o << std::string(9, ',');
      }
    } else {
      // Lost frames: empty fields, never made-up numbers.
      for (int k = 0; k < 11 + model_.num_expressions() + (options_.refine ? 9 : 0); ++k) o << ',';
    }
    write_gaze(f, o, row);
    o << ',' << f.shot << '\n';
    if (landmarks_)
      landmarks_->stream() << landmark_table_row(f.index, f.time, to_string(f.status), ok ? &f.fit : nullptr) << '\n';
    if (action_units_)
      action_units_->stream() << action_unit_table_->row(f.index, f.time, to_string(f.status),
                                                         unit_intensities ? &*unit_intensities : nullptr)
                              << '\n';
    if (livelink_face_) write_livelink(f);
    if (ok && head_chan_) write_chan(f);
    const std::string line = row.dump();
    jsonl_.stream() << line << '\n';
    if (options_.on_row) options_.on_row(line);
    if (ok && texture_ && texture_->wants_more()) texture_->add(f.image, coarse, camera);
    if (ok && options_.aligned_faces) write_aligned_face(f);
    if (ok) meshes_.add(f, shot_first_frame_, ref, coarse);
    if (detail_maps_) {
      if (ok && ref != nullptr && refiner_ != nullptr)
        detail_maps_->add(f.index, refiner_->hierarchy(), ref->displacement);
      else
        detail_maps_->add_flat(f.index);
    }
    if (uv_passes_) write_uv_pass(f, ref, coarse, camera);
    if (ok && animations_)
      append_animation_key(animations_->keys(f.shot, f.identity), has_timeline(info_), f.index, f.time, f.fit.pose,
                           f.fit.expression, key_gaze(f.fit.gaze));
    if (videos_) videos_->write(f, ref, refiner_, coarse, camera);
  }

  // What is written per shot (shot_animations.hpp): its albedo texture
  // (with --refine) and its glTF. The first shot with a face takes the plain
  // names, later ones `_shot<N>`. Called at a cut before the refiner starts
  // again (RefineStage::on_shot_end), and again harmlessly by the next
  // shot's first frame.
  void end_shot() {
    if (!shot_has_face_) {
      meshes_.end_shot();
      return;
    }
    shot_has_face_ = false;
    shot_albedo_png_.clear();
    if (refiner_ != nullptr) shot_albedo_png_ = face_albedo_png(model_, *refiner_);
    const fs::path* albedo = stage_shot_image(shot_albedo_png_, kAlbedoImage, albedo_files_);
    shot_texture_png_.clear();
    if (texture_ && !texture_->empty()) {
      cv::Mat texture8;
      texture_->texture().convertTo(texture8, CV_8UC3, 255.0);
      shot_texture_png_ = encode_png(texture8);
      texture_->clear();  // the next shot's comes from its own frames
    }
    const fs::path* texture = stage_shot_image(shot_texture_png_, kTextureImage, texture_files_);
    meshes_.end_shot(options_.texture ? texture : albedo);  // the OBJs' material names their texture
    if (animations_) animations_->end_shot();
  }

  void finish(const CaptureSummary& capture) {
    const IdentityEstimate& id = capture.identity;
    nlohmann::json j;
    j["format"] = "facecap-identity";
    j["version"] = 1;
    j["model"] = "ICT Face Model Light (ICT-FaceKit, MIT)";
    j["identity_weights"] = std::vector<double>(id.identity.data(), id.identity.data() + id.identity.size());
    j["identity_modes"] = id.identity.size();
    j["focal_px"] = id.focal;
    j["principal_point_px"] = {0.5 * info_.width, 0.5 * info_.height};
    j["image_size"] = {info_.width, info_.height};
    j["frames_used"] = id.frames_used;
    // Held as given (--identity), not solved from this input.
    j["identity_given"] = options_.capture.fit.known_identity.has_value();
    // The face's size, which landmarks hardly show (identity_size.hpp).
    j["size_correction"] = {{"factor", id.size_factor}, {"identity_modes_determined", id.effective_modes}};
    j["expression_names"] = model_.expression_names;
    // A video that cuts: the top-level identity is the first shot's; each
    // shot with a face has its own (frames.jsonl's "shot" says which).
    if (capture.cuts > 0) {
      nlohmann::json shots = nlohmann::json::array();
      for (const CaptureSummary::Shot& shot : capture.shots) {
        const Eigen::VectorXd& w = shot.identity.identity;
        shots.push_back({{"shot", shot.index},
                         {"first_frame", shot.first_frame},
                         {"identity_weights", std::vector<double>(w.data(), w.data() + w.size())},
                         {"focal_px", shot.identity.focal},
                         {"frames_used", shot.identity.frames_used},
                         {"size_correction", {{"factor", shot.identity.size_factor}}}});
      }
      j["shots"] = shots;
    }
    j["conventions"] = {
        {"units", "centimetres"},
        {"camera", "x right, y down, z forward (OpenCV); pixel centres at integer coordinates"},
        {"pose", "X_camera = R(rotation) * diag(1,-1,-1) * X_model + translation; rotation is axis-angle in radians"},
        {"model", "X_model = neutral + sum identity_i * (identity_i - neutral) + sum w_j * (expression_j - neutral)"},
        {"lighting",
         "l^T SH(n), SH(n) = (1, x, y, z, xy, xz, yz, x^2 - y^2, 3 z^2 - 1), n in the viewer frame "
         "(x right, y up, z toward the viewer), intensities in [0, 1]"}};
    // No face in any frame: there is no identity to report, only the lost rows
    // (and an identity.json of an earlier run in this folder would belie them).
    if (id.frames_used > 0) {
      write_text_file(dir_ / "identity.json", j.dump(2) + "\n");
    } else {
      std::error_code ec;
      fs::remove(dir_ / "identity.json", ec);
    }
    end_shot();
    // Like identity.json: no tracked frame, no face to animate (an earlier
    // run's animation.glb is removed, and so are its later shots' files).
    if (animations_) animation_files_ = animations_->finish();
    if (options_.gltf || options_.uv_pass) stage_face_matte(id.frames_used > 0);
    staged_images_.commit();
    if (options_.refine) remove_other_shot_files(dir_ / kAlbedoImage, albedo_files_, /*remove_first_when_none=*/false);
    if (options_.texture)
      remove_other_shot_files(dir_ / kTextureImage, texture_files_, /*remove_first_when_none=*/true);
    csv_.commit();
    jsonl_.commit();
    if (landmarks_) landmarks_->commit();
    if (action_units_) action_units_->commit();
    if (options_.aligned_faces) remove_unwritten_frame_files(dir_ / kAlignedFaces, {"png"}, aligned_written_);
    if (detail_maps_) detail_maps_->finish();
    if (uv_passes_) uv_passes_->finish();
    if (livelink_) livelink_->commit();
    if (head_chan_ && id.frames_used > 0) {
      head_chan_->commit();
      camera_chan_->commit();
      chan_files_ = {dir_ / kHeadChan, dir_ / kCameraChan};
    } else if (head_chan_) {  // like identity.json: no tracked frame, no motion to key
      std::error_code ec;
      fs::remove(dir_ / kHeadChan, ec);
      fs::remove(dir_ / kCameraChan, ec);
    }
    if (videos_) videos_->finish();
    meshes_.finish();
  }

  const fs::path& face_matte_file() const { return face_matte_file_; }
  const std::vector<fs::path>& chan_files() const { return chan_files_; }
  int meshes_written() const { return meshes_.meshes_written(); }
  int detail_maps_written() const { return detail_maps_ ? detail_maps_->maps_written() : 0; }
  int uv_passes_written() const { return uv_passes_ ? uv_passes_->passes_written() : 0; }
  const std::vector<fs::path>& animation_files() const { return animation_files_; }
  std::vector<fs::path> point_cache_files() const { return meshes_.point_cache_files(); }
  int gaze_frames() const { return gaze_frames_; }
  const LiveLinkStreamer* livelink_stream() const { return livelink_stream_ ? &*livelink_stream_ : nullptr; }
  void set_refiner(const Refiner* r) {
    refiner_ = r;
    meshes_.set_refiner(r);
  }

 private:
  // A shot's image (PNG bytes; none where empty) staged under its shot's
  // name (shot_file: the first shot with one takes `name`); returns where it
  // will be, or null.
  const fs::path* stage_shot_image(const std::vector<uint8_t>& png, const char* name, std::vector<fs::path>& files) {
    if (png.empty()) return nullptr;
    const fs::path file = shot_file(dir_ / name, shot_, files.empty());
    write_binary_file(staged_images_.stage(file), png.data(), png.size());
    files.push_back(file);
    return &files.back();
  }

  // --gltf, --uv-pass: the face matte (face_matte.hpp), the same for every
  // shot; where no face was tracked, none (an earlier run's is removed).
  void stage_face_matte(bool any_face) {
    const fs::path file = dir_ / kFaceMatteImage;
    if (!any_face) {
      std::error_code ec;
      fs::remove(file, ec);
      return;
    }
    const std::vector<uint8_t> png = encode_png(face_matte_image(model_));
    write_binary_file(staged_images_.stage(file), png.data(), png.size());
    face_matte_file_ = file;
  }

  // --livelink, --livelink-udp: the frame's weights, head angles and each
  // eye's gaze as Live Link Face values (io/livelink_face.hpp), a row of the
  // take and a datagram of the stream.
  // The fitted landmarks place the crop: steadier than the detector's, and
  // where the model puts the face.
  void write_aligned_face(const CapturedFrame& f) {
    const std::string name = frame_file_name(f.index, "png");
    write_image(dir_ / kAlignedFaces / name, aligned_face(f.image, f.fit.fitted, options_.aligned_face_size));
    aligned_written_.insert(name);
  }

  // --chan: the head's pose as a Nuke Axis node takes it, in Nuke's space
  // (core/view_frame.hpp: y up, the camera at the origin looking down -z),
  // in centimetres; and the camera's vertical field of view.
  void write_chan(const CapturedFrame& f) {
    const ViewPose view = pose_in_view_frame(f.fit.pose);
    const int frame = f.index + options_.chan_first_frame;
    head_chan_->stream() << chan_line(frame, view.translation, euler_zxy_degrees(view.rotation));
    const double vfov_deg = 2 * std::atan(0.5 * info_.height / f.fit.focal) * 180 / std::numbers::pi;
    camera_chan_->stream() << chan_line(frame, Vec3d::Zero(), Vec3d::Zero(), vfov_deg);
  }

  // --uv-pass: the refined surface where the frame was refined, else the
  // tracked one; an empty pass where no face was tracked.
  void write_uv_pass(const CapturedFrame& f, const Refinement* ref, const Positions& coarse,
                     const PinholeCamera& camera) {
    if (f.status == TrackStatus::kLost)
      uv_passes_->add_empty(f.index);
    else if (ref != nullptr && refiner_ != nullptr)
      uv_passes_->add(f.index, ref->positions, camera, &refiner_->hierarchy());
    else
      uv_passes_->add(f.index, coarse, camera);
  }

  void write_livelink(const CapturedFrame& f) {
    if (f.status != TrackStatus::kLost) {
      LiveLinkPose pose;
      pose.head_yaw_pitch_roll_deg = yaw_pitch_roll_deg(f.fit.pose.rotation_matrix());
      const GazeEstimate& g = f.fit.gaze;
      // Eye 0 is the subject's right; an eye not seen looks where the other does.
      const Vec2d both = g.valid() ? g.angles_deg() : Vec2d::Zero();
      pose.right_eye_deg = g.eyes[0] ? gaze_angles_deg(g.eyes[0]->direction) : both;
      pose.left_eye_deg = g.eyes[1] ? gaze_angles_deg(g.eyes[1]->direction) : both;
      livelink_values_ = livelink_face_->values(f.fit.expression, pose);
    }
    if (livelink_) livelink_->stream() << livelink_csv_->row(f.time, livelink_values_) << '\n';
    if (livelink_stream_) livelink_stream_->send(f.time, livelink_values_);
  }

  // Gaze (gaze.hpp): head-relative angles, the camera-frame direction and
  // the iris centres; empty fields and null where no iris was found. An eye
  // has a direction only where it has an iris.
  void write_gaze(const CapturedFrame& f, std::ofstream& o, nlohmann::json& row) {
    const GazeEstimate& g = f.fit.gaze;
    nlohmann::json gaze = nullptr;
    if (g.valid()) {
      ++gaze_frames_;
      const Vec2d angles = g.angles_deg();
      const Vec3d camera = f.fit.pose.model_to_camera_rotation() * g.direction();
      o << ',' << csv_number(angles.x()) << ',' << csv_number(angles.y());
      for (int k = 0; k < 3; ++k) o << ',' << csv_number(camera[k]);
      gaze = {{"yaw_deg", angles.x()},
              {"pitch_deg", angles.y()},
              {"direction_head", {g.direction().x(), g.direction().y(), g.direction().z()}},
              {"direction_camera", {camera.x(), camera.y(), camera.z()}}};
      for (int eye = 0; eye < 2; ++eye) {
        const char* side = eye == 0 ? "right" : "left";
        if (!g.eyes[eye]) {
          gaze[side] = nullptr;
          continue;
        }
        const Vec3d& d = g.eyes[eye]->direction;
        const IrisObservation& iris = *f.fit.irises[eye];
        gaze[side] = {{"iris_px", {iris.centre.x(), iris.centre.y()}},
                      {"iris_radius_px", iris.radius},
                      {"direction_head", {d.x(), d.y(), d.z()}}};
      }
    } else {
      o << std::string(5, ',');
    }
    for (int eye = 0; eye < 2; ++eye) {
      if (g.eyes[eye]) {
        o << ',' << csv_number(f.fit.irises[eye]->centre.x()) << ',' << csv_number(f.fit.irises[eye]->centre.y());
      } else {
        o << ",,";
      }
    }
    row["gaze"] = gaze;
  }

  const FaceModel& model_;
  InputInfo info_;
  std::string input_;
  fs::path dir_;
  const TrackOptions options_;  // a copy: a capture may outlive the options it was given
  StagedText csv_;
  StagedText jsonl_;
  std::optional<StagedText> landmarks_;     // --landmarks-csv (landmark_table.hpp)
  std::optional<StagedText> action_units_;  // --action-units (action_unit_table.hpp)
  std::optional<ActionUnitTable> action_unit_table_;
  std::unordered_set<std::string> aligned_written_;  // --aligned-faces: the crops' file names
  std::optional<DetailMaps> detail_maps_;            // --detail-maps
  std::optional<UvPasses> uv_passes_;                // --uv-pass
  // --livelink, --livelink-udp: a row and a datagram per frame; a lost frame
  // holds the last tracked one's values (importers read rows as frames, and
  // a rig keeps its face), the first ones the rest pose.
  std::optional<LiveLinkFace> livelink_face_;
  LiveLinkFace::Values livelink_values_{};
  std::optional<StagedText> livelink_;
  std::optional<LiveLinkCsv> livelink_csv_;
  std::optional<StagedText> head_chan_, camera_chan_;  // --chan
  std::vector<fs::path> chan_files_;                   // ...where they were written
  std::optional<LiveLinkStreamer> livelink_stream_;
  std::optional<TrackVideos> videos_;  // --overlay
  int gaze_frames_ = 0;
  const Refiner* refiner_ = nullptr;
  std::optional<ShotAnimations> animations_;
  std::vector<fs::path> animation_files_;
  int shot_ = 0;
  bool shot_has_face_ = false;
  std::vector<uint8_t> shot_albedo_png_;
  std::vector<fs::path> albedo_files_;
  std::optional<FaceTextureGatherer> texture_;  // --texture: the shot's first frames with a face
  std::vector<uint8_t> shot_texture_png_;
  std::vector<fs::path> texture_files_;
  StagedFiles staged_images_;  // each shot's albedo.png and texture.png, and face_matte.png, in place when the
                               // capture completes
  fs::path face_matte_file_;   // where one was written
  int shot_first_frame_ = -1;  // the index of the current shot's first frame
  TrackMeshes meshes_;         // --meshes, --point-cache
};

}  // namespace

struct TrackOutput::Impl {
  Impl(const FaceModel& model, const InputInfo& info, const std::string& input, const fs::path& dir,
       const TrackOptions& options)
      : model(model), info(info), input(input), options(options), writer(model, info, input, dir, options) {
    if (options.refine) {
      stage = std::make_unique<RefineStage>(model, options.refine_options, [this](const RefinedFrame& r) {
        if (this->options.on_frame) this->options.on_frame(r.frame);
        writer.write(r.frame, r.refinement ? &*r.refinement : nullptr, r.coarse, r.camera);
      });
      writer.set_refiner(&stage->refiner());
      stage->on_shot_end([this] { writer.end_shot(); });
    }
  }

  void take(const CapturedFrame& f) {
    if (stage) {
      stage->push(f);  // refined on the stage's thread, concurrently with the next frames' tracking
      return;
    }
    if (options.on_frame) options.on_frame(f);
    Positions coarse;
    PinholeCamera cam;
    if (f.status != TrackStatus::kLost) {
      coarse = to_camera(face_shape.evaluate(f.identity.identity.cast<float>(), f.fit.expression), f.fit.pose);
      cam = PinholeCamera::centered(f.fit.focal, info.width, info.height);
    }
    writer.write(f, nullptr, coarse, cam);
  }

  const FaceModel& model;
  const InputInfo info;
  const std::string input;
  const TrackOptions options;
  FrameWriter writer;
  FaceShapeCache face_shape{model, regions::kFace};
  std::unique_ptr<RefineStage> stage;
};

TrackOutput::TrackOutput(const FaceModel& model, const InputInfo& info, const std::string& input, const fs::path& dir,
                         const TrackOptions& options) {
  ensure_writable_dir(dir);
  // Re-tracking an earlier run's overlay into its own folder would replace it.
  for (const std::string& name : TrackVideos::file_names()) ensure_not_an_input(dir / name, {input});
  for (const char* name : {kAlbedoImage, kTextureImage}) ensure_not_an_input(dir / name, {input});
  impl_ = std::make_unique<Impl>(model, info, input, dir, options);
  output_dir_ = dir;
}

TrackOutput::~TrackOutput() = default;

FrameSink TrackOutput::sink() {
  return [this](const CapturedFrame& f) { impl_->take(f); };
}

TrackSummary TrackOutput::finish(const CaptureSummary& capture) {
  TrackSummary summary;
  summary.output_dir = output_dir_;
  summary.capture = capture;
  if (impl_->stage) {
    impl_->stage->finish();
    summary.refined_frames = impl_->stage->refined_frames();
    summary.refine_ms = impl_->stage->refine_ms();
  }
  if (summary.capture.frames == 0) throw Error("no frames could be read from " + impl_->input);
  impl_->writer.finish(summary.capture);
  summary.animation_files = impl_->writer.animation_files();
  summary.point_cache_files = impl_->writer.point_cache_files();
  summary.meshes_written = impl_->writer.meshes_written();
  summary.detail_maps = impl_->writer.detail_maps_written();
  summary.uv_passes = impl_->writer.uv_passes_written();
  summary.face_matte = impl_->writer.face_matte_file();
  summary.chan_files = impl_->writer.chan_files();
  summary.gaze_frames = impl_->writer.gaze_frames();
  if (const LiveLinkStreamer* stream = impl_->writer.livelink_stream()) {
    summary.livelink_sent = stream->sent();
    summary.livelink_address = stream->address();
    summary.livelink_error = stream->first_error();
  }
  return summary;
}

TrackSummary run_track(const FaceModel& model, const std::string& input, const fs::path& dir,
                       const TrackOptions& options) {
  auto source = open_input(input, options.capture.start_seconds);  // validates the input before anything is written
  return run_track(model, *source, input, dir, options);
}

TrackSummary run_track(const FaceModel& model, FrameSource& source, const std::string& input, const fs::path& dir,
                       const TrackOptions& options) {
  TrackOutput output(model, source.info(), input, dir, options);
  CaptureOptions capture = options.capture;
  capture.keep_images = options.needs_images();
  return output.finish(run_capture(model, source, capture, output.sink()));
}

}  // namespace facecap
