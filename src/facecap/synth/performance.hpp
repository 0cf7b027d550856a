#pragma once
// The known parameters of a synthetic performance: identity, per-frame
// expression weights, head pose and SH lighting, and the camera. `facecap
// synth` renders them; every estimator is tested by recovering them.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap {

struct SynthOptions {
  int frames = 90;
  // Render only the first this many frames of the performance, whose course
  // is still that of `frames` (0: all of them); the truth lists those rendered.
  int render_frames = 0;
  uint64_t seed = 1;
  int width = 640;
  int height = 480;
  double fps = 30.0;
  double focal = 0.0;         // pixels; 0 = 1.1 x width
  double max_yaw_deg = 30.0;  // head turns sweep +-this
  double max_pitch_deg = 8.0;
  double max_roll_deg = 5.0;
  // The camera turned about its axis (on its side: 90): the whole
  // performance rolls in the image by this many degrees, clockwise (the eye
  // line's angle, roll_degrees()), its lighting with it.
  double camera_roll_deg = 0.0;
  double face_height = 0.45;  // chin-to-brow height as a share of the image height
  bool still = false;         // hold pose and expression (for jitter measurements)
  bool detail = false;        // wrinkle-like displacements along the normals
  int identity_modes = 50;    // random identity on the leading modes, N(0, 1)
  double noise_sigma = 1.5;   // sensor noise, 0-255 grey levels
  // The face's skin: a texture in the ICT face UV layout (BGR CV_32FC3 in
  // [0, 1], square, row 0 at v = 1), such as face_texture_from_photo()
  // makes of a real portrait; empty: skin painted from the seed
  // (skin_albedo.hpp). `face_texture_source`: the file it came from, which
  // the output's marks name.
  cv::Mat face_texture;
  std::string face_texture_source;

  // Throws facecap::Error naming the bad option.
  void check() const;
};

struct SynthFrame {
  int index = 0;
  double time = 0.0;
  HeadPose pose;
  Eigen::VectorXf expression;      // one weight per model expression, in [0, 1]
  ShCoeffs lighting;               // viewer-frame SH, shared by the colour channels
  Vec2d gaze_deg = Vec2d::Zero();  // both eyes' (yaw, pitch), head-relative (eyeballs.hpp)
};

struct SynthPerformance {
  SynthOptions options;
  PinholeCamera camera;
  Eigen::VectorXf identity;  // all model identity modes (zeros past identity_modes)
  std::vector<SynthFrame> frames;
  Vec3f skin_tone{0.78f, 0.56f, 0.45f};  // base albedo, RGB
};

// Draws a performance: smooth talking-like jaw and lip motion, blinks and
// occasional expressions (smile, brow raise, frown), head turns of up to
// +-max_yaw_deg, gaze that wanders with the lids following it, and slowly
// varying lighting, all reproducible from the seed.
SynthPerformance make_performance(const FaceModel& model, const SynthOptions& options);

}  // namespace facecap
