#include "facecap/synth/truth_io.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

using nlohmann::json;

json landmarks_json(const Landmarks& lm) {
  json a = json::array();
  for (const Vec2f& p : lm) a.push_back({p.x(), p.y()});
  return a;
}

Landmarks landmarks_from(const json& a) {
  if (!a.is_array() || a.size() != kNumLandmarks) throw Error("expected 68 landmarks");
  Landmarks lm;
  for (int i = 0; i < kNumLandmarks; ++i) lm[i] = Vec2f(a[i][0].get<float>(), a[i][1].get<float>());
  return lm;
}

template <typename V>
json vec(const V& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

}  // namespace

void write_truth(const std::filesystem::path& path, const SynthTruth& truth) {
  const SynthPerformance& p = truth.performance;
  const SynthOptions& o = p.options;
  json j;
  j["format"] = "facecap-synth-truth";
  j["version"] = 1;
  j["synthetic"] = true;
  j["options"] = {{"frames", o.frames},
                  {"render_frames", o.render_frames},
                  {"seed", o.seed},
                  {"width", o.width},
                  {"height", o.height},
                  {"fps", o.fps},
                  {"max_yaw_deg", o.max_yaw_deg},
                  {"max_pitch_deg", o.max_pitch_deg},
                  {"max_roll_deg", o.max_roll_deg},
                  {"camera_roll_deg", o.camera_roll_deg},
                  {"face_height", o.face_height},
                  {"still", o.still},
                  {"detail", o.detail},
                  {"identity_modes", o.identity_modes},
                  {"noise_sigma", o.noise_sigma}};
  j["camera"] = {{"focal", p.camera.focal}, {"cx", p.camera.cx}, {"cy", p.camera.cy}};
  j["identity"] = vec(p.identity);
  j["skin_tone_rgb"] = vec(p.skin_tone);
  j["expression_names"] = truth.expression_names;
  j["units"] = {{"translation", "cm"},
                {"rotation", "axis-angle radians, camera frame x right y down z forward"},
                {"landmarks", "pixels, 0-based, pixel centres at integers"},
                {"gaze", "degrees, head-relative: yaw toward the subject's left, pitch up; both eyes"}};
  json frames = json::array();
  for (size_t f = 0; f < p.frames.size(); ++f) {
    const SynthFrame& fr = p.frames[f];
    const Vec3d ypr = yaw_pitch_roll_deg(fr.pose.rotation_matrix());
    frames.push_back({{"index", fr.index},
                      {"time", fr.time},
                      {"rotation", vec(fr.pose.rotation)},
                      {"yaw_pitch_roll_deg", vec(ypr)},
                      {"translation", vec(fr.pose.translation)},
                      {"expression", vec(fr.expression)},
                      {"lighting", vec(fr.lighting)},
                      {"gaze_yaw_pitch_deg", vec(fr.gaze_deg)},
                      {"landmarks", landmarks_json(truth.landmarks[f])},
                      {"landmark_vertices", landmarks_json(truth.vertex_landmarks[f])}});
  }
  j["frames"] = frames;
  write_text_file(path, j.dump(1));
}

SynthTruth read_truth(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("truth file not found: " + path.string());
  try {
    const json j = json::parse(in);
    if (j.value("format", "") != "facecap-synth-truth") throw Error("not a facecap truth file");
    SynthTruth t;
    SynthPerformance& p = t.performance;
    const json& o = j.at("options");
    p.options.frames = o.at("frames");
    p.options.render_frames = o.value("render_frames", 0);
    p.options.seed = o.at("seed");
    p.options.width = o.at("width");
    p.options.height = o.at("height");
    p.options.fps = o.at("fps");
    p.options.max_yaw_deg = o.at("max_yaw_deg");
    p.options.max_pitch_deg = o.at("max_pitch_deg");
    p.options.max_roll_deg = o.at("max_roll_deg");
    p.options.camera_roll_deg = o.value("camera_roll_deg", 0.0);
    p.options.face_height = o.at("face_height");
    p.options.still = o.at("still");
    p.options.detail = o.at("detail");
    p.options.identity_modes = o.at("identity_modes");
    p.options.noise_sigma = o.at("noise_sigma");
    p.camera.focal = j.at("camera").at("focal");
    p.camera.cx = j.at("camera").at("cx");
    p.camera.cy = j.at("camera").at("cy");
    const auto id = j.at("identity").get<std::vector<float>>();
    p.identity = Eigen::Map<const Eigen::VectorXf>(id.data(), static_cast<Eigen::Index>(id.size()));
    const auto tone = j.at("skin_tone_rgb").get<std::vector<float>>();
    p.skin_tone = Vec3f(tone.at(0), tone.at(1), tone.at(2));
    t.expression_names = j.at("expression_names").get<std::vector<std::string>>();
    for (const json& f : j.at("frames")) {
      SynthFrame fr;
      fr.index = f.at("index");
      fr.time = f.at("time");
      const auto r = f.at("rotation").get<std::vector<double>>();
      const auto tr = f.at("translation").get<std::vector<double>>();
      fr.pose.rotation = Vec3d(r.at(0), r.at(1), r.at(2));
      fr.pose.translation = Vec3d(tr.at(0), tr.at(1), tr.at(2));
      const auto w = f.at("expression").get<std::vector<float>>();
      fr.expression = Eigen::Map<const Eigen::VectorXf>(w.data(), static_cast<Eigen::Index>(w.size()));
      const auto l = f.at("lighting").get<std::vector<double>>();
      if (l.size() != 9) throw Error("lighting must have 9 coefficients");
      for (int k = 0; k < 9; ++k) fr.lighting[k] = l[k];
      if (f.contains("gaze_yaw_pitch_deg")) {  // absent from truth files before gaze
        const auto g = f.at("gaze_yaw_pitch_deg").get<std::vector<double>>();
        if (g.size() != 2) throw Error("gaze must have 2 angles");
        fr.gaze_deg = Vec2d(g[0], g[1]);
      }
      p.frames.push_back(fr);
      t.landmarks.push_back(landmarks_from(f.at("landmarks")));
      t.vertex_landmarks.push_back(landmarks_from(f.at("landmark_vertices")));
    }
    return t;
  } catch (const Error& e) {
    throw Error("malformed truth file " + path.string() + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {
    throw Error("malformed truth file " + path.string() + ": " + e.what());
  }
}

}  // namespace facecap
