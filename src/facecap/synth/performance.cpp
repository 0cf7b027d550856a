#include "facecap/synth/performance.hpp"

#include <cmath>
#include <random>

#include "facecap/core/error.hpp"
#include "facecap/model/eye_look.hpp"

namespace facecap {

namespace {

// SH lighting `l` of a scene turned by `r` (viewer frame): l' with
// l'^T SH(n) = l^T SH(r^T n) for every normal. The basis spans the
// polynomials of degree 2 on the sphere, which rotations keep, so fitting
// l' on nine or more normals is exact.
ShCoeffs turned(const ShCoeffs& l, const Mat3d& r) {
  constexpr int kNormals = 32;
  Eigen::Matrix<double, kNormals, 9> a;
  Eigen::Matrix<double, kNormals, 1> b;
  for (int i = 0; i < kNormals; ++i) {
    // A spiral over the sphere.
    const double z = 1.0 - (2.0 * i + 1.0) / kNormals, phi = 2.399963229728653 * i;
    const Vec3d n(std::sqrt(1.0 - z * z) * std::cos(phi), std::sqrt(1.0 - z * z) * std::sin(phi), z);
    const Vec3d before = r.transpose() * n;
    a.row(i) = sh_basis(n.x(), n.y(), n.z()).transpose();
    b[i] = sh_shade(l, before.x(), before.y(), before.z());
  }
  return a.colPivHouseholderQr().solve(b);
}

constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const std::string& what) {
  if (!ok) throw Error("synth: " + what);
}

// Band-limited noise in about [-1, 1]: a few sinusoids of random frequency and phase.
struct SmoothNoise {
  std::vector<double> freq, phase;
  SmoothNoise(std::mt19937_64& rng, double f_lo, double f_hi, int terms = 4) {
    std::uniform_real_distribution<double> f(f_lo, f_hi), p(0, 2 * kPi);
    for (int i = 0; i < terms; ++i) {
      freq.push_back(f(rng));
      phase.push_back(p(rng));
    }
  }
  double operator()(double t) const {
    double s = 0;
    for (size_t i = 0; i < freq.size(); ++i) s += std::sin(2 * kPi * freq[i] * t + phase[i]);
    return s / std::sqrt(double(freq.size()) * 0.5) * 0.5;
  }
};

// Raised-cosine bump: 0 outside [centre - width/2, centre + width/2], 1 at the centre.
double bump(double t, double centre, double width) {
  const double x = (t - centre) / (0.5 * width);
  return std::abs(x) >= 1 ? 0.0 : 0.5 * (1 + std::cos(kPi * x));
}

// An occasional expression: weights of named shapes that rise and fall together.
struct ExpressionEvent {
  std::vector<std::pair<std::string, double>> shapes;
  double centre = 0, width = 1, intensity = 1, asymmetry = 0;
};

}  // namespace

void SynthOptions::check() const {
  require(frames >= 1 && frames <= 100000, "--frames must be between 1 and 100000");
  require(render_frames >= 0 && render_frames <= frames, "the frames to render must be between 0 (all) and --frames");
  require(width >= 64 && height >= 64 && width <= 8192 && height <= 8192, "--size must be between 64x64 and 8192x8192");
  require(fps > 0 && fps <= 240, "fps must be in (0, 240]");
  require(focal >= 0, "--focal must be positive");
  require(max_yaw_deg >= 0 && max_yaw_deg <= 60, "--yaw must be between 0 and 60 degrees");
  require(camera_roll_deg >= -180 && camera_roll_deg <= 180, "--roll must be between -180 and 180 degrees");
  require(face_height > 0.05 && face_height < 1.5, "face height share must be in (0.05, 1.5)");
  require(identity_modes >= 0 && identity_modes <= 100, "identity modes must be in [0, 100]");
  require(noise_sigma >= 0 && noise_sigma <= 50, "noise sigma must be in [0, 50]");
  require(face_texture.empty() ||
              (face_texture.type() == CV_32FC3 && face_texture.rows == face_texture.cols && face_texture.rows >= 16),
          "a face texture must be square, 3-channel float and at least 16 texels wide");
}

SynthPerformance make_performance(const FaceModel& model, const SynthOptions& options) {
  options.check();
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  SynthPerformance perf;
  perf.options = options;
  const double focal = options.focal > 0 ? options.focal : 1.1 * options.width;
  perf.camera = PinholeCamera::centered(focal, options.width, options.height);

  perf.identity = Eigen::VectorXf::Zero(model.num_identity());
  for (int i = 0; i < std::min(options.identity_modes, model.num_identity()); ++i) {
    perf.identity[i] = static_cast<float>(std::clamp(normal(rng), -2.5, 2.5));
  }
  // Skin tones from light to dark, slightly varied.
  const Vec3f tones[] = {{0.86f, 0.66f, 0.56f}, {0.78f, 0.56f, 0.45f}, {0.64f, 0.44f, 0.33f}, {0.45f, 0.30f, 0.22f}};
  perf.skin_tone = tones[rng() % 4] * float(0.95 + 0.1 * uniform(rng));

  // Distance at which the brow-to-chin height (about 13.8 cm) fills face_height of the image.
  const double distance = focal * 13.8 / (options.face_height * options.height);
  const Vec3d face_centre_model(0.0, -0.65, 10.0);
  const Vec3d flipped_centre(face_centre_model.x(), -face_centre_model.y(), -face_centre_model.z());

  const double duration = options.frames / options.fps;
  const double motion = options.still ? 0.0 : 1.0;
  // One full yaw sweep over the sequence, at most 4 s long, so short clips still turn.
  const double yaw_period = std::clamp(duration, 2.0, 4.0);
  const double yaw_phase = uniform(rng) * 2 * kPi;
  const SmoothNoise pitch_noise(rng, 0.1, 0.4), roll_noise(rng, 0.1, 0.4), tx_noise(rng, 0.05, 0.3),
      ty_noise(rng, 0.05, 0.3), tz_noise(rng, 0.05, 0.2);

  // Speech: syllable-rate jaw motion and lip shapes.
  const SmoothNoise jaw(rng, 2.0, 5.0), lips_a(rng, 1.5, 4.0), lips_b(rng, 1.0, 3.5), lips_c(rng, 1.0, 3.0),
      gaze_x(rng, 0.1, 0.5), gaze_y(rng, 0.1, 0.5);

  std::vector<ExpressionEvent> events;
  const std::vector<std::vector<std::pair<std::string, double>>> kinds = {
      {{"mouthSmile_L", 1.0},
       {"mouthSmile_R", 1.0},
       {"cheekSquint_L", 0.6},
       {"cheekSquint_R", 0.6},
       {"eyeSquint_L", 0.3},
       {"eyeSquint_R", 0.3}},
      {{"browInnerUp_L", 1.0},
       {"browInnerUp_R", 1.0},
       {"browOuterUp_L", 0.8},
       {"browOuterUp_R", 0.8},
       {"eyeWide_L", 0.5},
       {"eyeWide_R", 0.5}},
      {{"browDown_L", 0.9},
       {"browDown_R", 0.9},
       {"mouthFrown_L", 0.6},
       {"mouthFrown_R", 0.6},
       {"noseSneer_L", 0.3},
       {"noseSneer_R", 0.3}},
      {{"mouthPucker", 0.8}, {"mouthFunnel", 0.4}},
      {{"mouthStretch_L", 0.6}, {"mouthStretch_R", 0.6}, {"mouthDimple_L", 0.5}, {"mouthDimple_R", 0.5}}};
  if (!options.still) {
    // About one expression every 1.5 s, at least two per clip, cycling through the kinds.
    const int count = std::max(2, static_cast<int>(duration / 1.5));
    const size_t first_kind = rng() % kinds.size();
    for (int e = 0; e < count; ++e) {
      ExpressionEvent ev;
      ev.shapes = kinds[(first_kind + e) % kinds.size()];
      ev.centre = duration * (e + 0.5 + 0.3 * (uniform(rng) - 0.5)) / count;
      ev.width = std::clamp(duration / count * 1.6, 0.6, 2.5);
      ev.intensity = 0.45 + 0.5 * uniform(rng);
      ev.asymmetry = 0.3 * (uniform(rng) - 0.5);
      events.push_back(ev);
    }
  }
  std::vector<double> blinks;
  for (double t = 0.4 + 1.5 * uniform(rng); t < duration; t += 2.0 + 2.0 * uniform(rng)) blinks.push_back(t);

  const EyeLookShapes eye_look(model);
  auto set = [&](Eigen::VectorXf& w, const std::string& name, double value) {
    const int i = model.expression_index(name);
    if (i >= 0) w[i] = static_cast<float>(std::clamp(double(w[i]) + value, 0.0, 1.0));
  };

  // Lighting: a random key light direction and strength; fixed per clip apart from a slow drift.
  ShCoeffs base_light;
  for (;;) {
    const double az = (uniform(rng) - 0.5) * 1.6, el = 0.2 + 0.6 * uniform(rng);
    const Vec3d dir(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    const double key = 0.25 + 0.2 * uniform(rng);
    base_light << 0.75 + 0.1 * uniform(rng), key * dir.x(), key * dir.y(), key * dir.z(), 0.04 * normal(rng),
        0.04 * normal(rng), 0.04 * normal(rng), 0.04 * normal(rng), 0.03 + 0.03 * normal(rng);
    // Keep every front-facing normal lit (no negative irradiance).
    double lowest = 1e9;
    for (double a = -1.4; a <= 1.4; a += 0.1) {
      for (double b = -1.4; b <= 1.4; b += 0.1) {
        const Vec3d n(std::sin(a) * std::cos(b), std::sin(b), std::cos(a) * std::cos(b));
        lowest = std::min(lowest, sh_shade(base_light, n.x(), n.y(), n.z()));
      }
    }
    if (lowest > 0.2) break;
  }
  const SmoothNoise light_drift(rng, 0.05, 0.2);

  for (int f = 0; f < options.frames; ++f) {
    const double t = f / options.fps;
    SynthFrame frame;
    frame.index = f;
    frame.time = t;
    const double yaw = motion * options.max_yaw_deg * std::sin(2 * kPi * t / yaw_period + yaw_phase);
    const double pitch = motion * options.max_pitch_deg * pitch_noise(t);
    const double roll = motion * options.max_roll_deg * roll_noise(t);
    const Mat3d r = rotation_from_yaw_pitch_roll_deg(yaw, pitch, roll);
    const Vec3d centre(motion * 1.5 * tx_noise(t), motion * 1.0 * ty_noise(t), distance + motion * 3.0 * tz_noise(t));
    // A camera rolled by the angle sees the scene turned the other way about
    // its axis: in its frame (y down) everything turns clockwise by it.
    const Mat3d camera_roll =
        Eigen::AngleAxisd(options.camera_roll_deg * kPi / 180.0, Vec3d::UnitZ()).toRotationMatrix();
    frame.pose.rotation = axis_angle_from_rotation(camera_roll * r);
    frame.pose.translation = camera_roll * (centre - r * flipped_centre);

    Eigen::VectorXf w = Eigen::VectorXf::Zero(model.num_expressions());
    if (!options.still) {
      const double open = std::max(0.0, 0.18 + 0.22 * jaw(t));
      set(w, "jawOpen", open);
      set(w, "mouthLowerDown_L", std::max(0.0, 0.25 * lips_a(t)));
      set(w, "mouthLowerDown_R", std::max(0.0, 0.25 * lips_a(t)));
      set(w, "mouthUpperUp_L", std::max(0.0, 0.2 * lips_b(t)));
      set(w, "mouthUpperUp_R", std::max(0.0, 0.2 * lips_b(t)));
      set(w, "mouthFunnel", std::max(0.0, 0.3 * lips_c(t)));
      set(w, "mouthClose", std::max(0.0, -0.15 * jaw(t)));
      set(w, "mouthRollLower", std::max(0.0, -0.2 * lips_b(t)));
      // The eyeballs turn (ICT's shapes move only the lids) and the lids follow by facecap's convention.
      frame.gaze_deg = Vec2d(std::clamp(25.0 * gaze_x(t), -30.0, 30.0), std::clamp(15.0 * gaze_y(t), -20.0, 20.0));
      for (const auto& [k, weight] : eye_look.weights(frame.gaze_deg)) w[k] = static_cast<float>(weight);
      for (const ExpressionEvent& ev : events) {
        const double b = ev.intensity * bump(t, ev.centre, ev.width);
        if (b <= 0) continue;
        for (const auto& [name, weight] : ev.shapes) {
          const double side = name.ends_with("_L") ? 1 + ev.asymmetry : name.ends_with("_R") ? 1 - ev.asymmetry : 1;
          set(w, name, b * weight * side);
        }
      }
      for (double tb : blinks) {
        const double b = bump(t, tb, 0.3);
        set(w, "eyeBlink_L", b);
        set(w, "eyeBlink_R", b);
      }
    }
    frame.expression = w;
    frame.lighting = base_light;
    frame.lighting[0] += 0.03 * light_drift(t) * motion;
    // The lighting turns with the scene in the frame it is evaluated in, the
    // viewer's (y up, z toward the viewer: shading.hpp), where the camera's
    // clockwise turn is the other way round. (Turned in the camera's frame,
    // a 180 degree roll came out right and a 90 degree one lit the face from
    // the opposite side.)
    if (options.camera_roll_deg != 0) {
      const Mat3d viewer = Vec3d(1, -1, -1).asDiagonal();
      frame.lighting = turned(frame.lighting, viewer * camera_roll * viewer);
    }
    perf.frames.push_back(frame);
  }
  return perf;
}

}  // namespace facecap
