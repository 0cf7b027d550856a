#include "facecap/pipeline/track_job.hpp"

#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/version.hpp"
#include "facecap/io/mesh_writer.hpp"
#include "facecap/io/video_writer.hpp"
#include "facecap/render/overlay.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A text output written through a temporary file and renamed at the end.
class StagedText {
 public:
  explicit StagedText(const fs::path& path) : file_(path), out_(file_.temp_path()) {
    if (!out_) throw Error("cannot write " + path.string());
  }
  std::ofstream& stream() { return out_; }
  void commit() {
    out_.flush();
    if (!out_) throw Error("cannot write " + file_.final_path().string());
    out_.close();
    file_.commit();
  }

 private:
  AtomicFile file_;
  std::ofstream out_;
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

nlohmann::json landmarks_json(const Landmarks& lm) {
  nlohmann::json a = nlohmann::json::array();
  for (const Vec2f& p : lm) a.push_back({std::round(p.x() * 100) / 100, std::round(p.y() * 100) / 100});
  return a;
}

}  // namespace

TrackSummary run_track(const FaceModel& model, const std::string& input, const fs::path& dir,
                       const TrackOptions& options) {
  auto source = open_input(input);  // validates the input before anything is written
  ensure_writable_dir(dir);
  const InputInfo info = source->info();
  TrackSummary summary;
  summary.output_dir = dir;

  StagedText csv(dir / "frames.csv");
  StagedText jsonl(dir / "frames.jsonl");
  {
    std::ofstream& o = csv.stream();
    o << "frame,time,status,rx,ry,rz,tx,ty,tz,focal,yaw_deg,pitch_deg,roll_deg,landmark_error";
    for (const std::string& name : model.expression_names) o << ',' << name;
    o << '\n';
  }
  if (options.meshes) fs::create_directories(dir / "meshes");
  std::unique_ptr<VideoWriter> overlay;
  if (options.overlay) {
    VideoWriterOptions vo;
    vo.width = info.width;
    vo.height = info.height;
    vo.fps = info.fps > 0 ? info.fps : 25.0;
    if (info.audio) vo.audio_source = fs::path(input);
    vo.metadata = {{"comment", "facecap track overlay of " + fs::path(input).filename().string()}};
    overlay = std::make_unique<VideoWriter>(dir / "overlay.mp4", vo);
  }

  // Face-region topology and UVs for meshes and the wireframe.
  std::vector<Polygon> face_polygons(model.polygons.begin(), model.polygons.begin() + regions::kFace.num_polygons());
  const PinholeCamera cam_at_centre{1.0, 0.5 * info.width, 0.5 * info.height};

  CaptureOptions capture = options.capture;
  capture.keep_images = options.overlay;
  summary.capture = run_capture(model, *source, capture, [&](const CapturedFrame& f) {
    if (options.on_frame) options.on_frame(f);
    const bool ok = f.status != TrackStatus::kLost;
    std::ofstream& o = csv.stream();
    o << f.index << ',' << number(f.time) << ',' << to_string(f.status);
    nlohmann::json row = {{"frame", f.index}, {"time", f.time}, {"status", to_string(f.status)}};
    if (ok) {
      const Vec3d ypr = yaw_pitch_roll_deg(f.fit.pose.rotation_matrix());
      for (int k = 0; k < 3; ++k) o << ',' << number(f.fit.pose.rotation[k]);
      for (int k = 0; k < 3; ++k) o << ',' << number(f.fit.pose.translation[k]);
      o << ',' << number(f.fit.focal);
      for (int k = 0; k < 3; ++k) o << ',' << number(ypr[k]);
      o << ',' << number(f.fit.landmark_error);
      for (Eigen::Index k = 0; k < f.fit.expression.size(); ++k) o << ',' << number(f.fit.expression[k]);
      nlohmann::json weights;
      for (Eigen::Index k = 0; k < f.fit.expression.size(); ++k) weights[model.expression_names[k]] = f.fit.expression[k];
      row["rotation"] = {f.fit.pose.rotation.x(), f.fit.pose.rotation.y(), f.fit.pose.rotation.z()};
      row["translation"] = {f.fit.pose.translation.x(), f.fit.pose.translation.y(), f.fit.pose.translation.z()};
      row["yaw_pitch_roll_deg"] = {ypr.x(), ypr.y(), ypr.z()};
      row["focal"] = f.fit.focal;
      row["landmark_error"] = f.fit.landmark_error;
      row["weights"] = weights;
      row["landmarks"] = landmarks_json(f.fit.observed);
      row["fitted_landmarks"] = landmarks_json(f.fit.fitted);
    } else {
      // Lost frames: empty fields, never made-up numbers.
      for (int k = 0; k < 11 + model.num_expressions(); ++k) o << ',';
    }
    o << '\n';
    jsonl.stream() << row.dump() << '\n';

    if (!ok && !overlay) return;
    Positions shape;
    if (ok) shape = model.evaluate(f.identity->identity.cast<float>(), f.fit.expression, regions::kFace);
    if (ok && options.meshes) {
      const Positions out = options.mesh_space == MeshSpace::kCamera ? to_camera(shape, f.fit.pose) : shape;
      char name[64];
      std::snprintf(name, sizeof(name), "frame_%06d.obj", f.index);
      write_obj(dir / "meshes" / name,
                {&out, &face_polygons, &model.uvs,
                 "facecap " + std::string(kFacecapVersion) + " frame " + std::to_string(f.index) +
                     (options.mesh_space == MeshSpace::kCamera ? "\ncamera space (x right, y down, z forward), cm"
                                                               : "\nICT model space (y up, z out of the face), cm")});
      ++summary.meshes_written;
    }
    if (overlay) {
      cv::Mat canvas = f.image.clone();
      if (ok) {
        PinholeCamera cam = cam_at_centre;
        cam.focal = f.fit.focal;
        draw_wireframe(canvas, to_camera(shape, f.fit.pose), face_polygons, cam, cv::Scalar(255, 200, 80));
        draw_landmarks(canvas, f.fit.observed, cv::Scalar(0, 255, 0));
        draw_landmarks(canvas, f.fit.fitted, cv::Scalar(0, 0, 255), 1);
      }
      draw_caption(canvas, "frame " + std::to_string(f.index) + "  " + to_string(f.status));
      overlay->write(canvas);
    }
  });
  if (summary.capture.frames == 0) throw Error("no frames could be read from " + input);

  // identity.json
  const IdentityEstimate& id = summary.capture.identity;
  nlohmann::json j;
  j["format"] = "facecap-identity";
  j["version"] = 1;
  j["model"] = "ICT Face Model Light (ICT-FaceKit, MIT)";
  j["identity_weights"] = std::vector<double>(id.identity.data(), id.identity.data() + id.identity.size());
  j["identity_modes"] = id.identity.size();
  j["focal_px"] = id.focal;
  j["principal_point_px"] = {0.5 * info.width, 0.5 * info.height};
  j["image_size"] = {info.width, info.height};
  j["frames_used"] = id.frames_used;
  j["expression_names"] = model.expression_names;
  j["conventions"] = {
      {"units", "centimetres"},
      {"camera", "x right, y down, z forward (OpenCV); pixel centres at integer coordinates"},
      {"pose", "X_camera = R(rotation) * diag(1,-1,-1) * X_model + translation; rotation is axis-angle in radians"},
      {"model", "X_model = neutral + sum identity_i * (identity_i - neutral) + sum w_j * (expression_j - neutral)"}};
  write_text_file(dir / "identity.json", j.dump(2) + "\n");
  csv.commit();
  jsonl.commit();
  if (overlay) overlay->finish();
  return summary;
}

}  // namespace facecap
