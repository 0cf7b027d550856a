#pragma once
// `facecap eval track`: the coarse tracker measured against ground truth.
//  - synthetic: a `facecap synth` performance is fitted from its true 2D
//    landmarks plus Gaussian noise, or from dlib's landmarks on the rendered
//    video; shape, rotation, focal and weight errors against the truth, and
//    frame-to-frame jitter on a still-head sequence.
//  - video: real footage; how well the fitted model explains the detected
//    landmarks (no 3D truth exists), and lost frames.
#include <cstdint>
#include <string>

#include "facecap/pipeline/capture_session.hpp"
#include "facecap/synth/performance.hpp"

namespace facecap {

enum class LandmarkSource { kTruth, kDlib };

struct TrackEvalOptions {
  int frames = 90;
  uint64_t seed = 1;
  LandmarkSource landmarks = LandmarkSource::kTruth;
  double landmark_noise_px = 1.0;  // Gaussian, per coordinate (truth landmarks only)
  int still_frames = 30;           // still-head sequence for the jitter measurement (0: skip)
  SynthOptions synth;              // size, yaw range, ...; frames and seed are set from above
  CaptureOptions capture;          // capture.gaze: also the irises and gaze (truth landmarks: renders the frames)
  // Diagnostics: hold the focal length at the synthetic camera's
  // (capture.fit.focal_known), and the identity at the synthetic truth (its
  // leading capture.fit.identity_modes values; capture.fit.known_identity),
  // so that the vertex error measures what the landmarks give the
  // expressions and the pose alone: the floor under the error of a fit that
  // also solves the identity from the same landmarks.
  bool true_focal = false;
  bool true_identity = false;
};

// `options` with capture.fit holding what true_focal and true_identity ask
// of `perf`'s truth.
TrackEvalOptions with_truth_held(const TrackEvalOptions& options, const SynthPerformance& perf);

// The least standard deviation (0-5 scale) of a unit's true intensity over
// the frames for TrackEvalResult::action_units_correlation to count it.
inline constexpr double kActionUnitMovesFrom = 0.25;

// The least spread of true yaw over which TrackEvalResult::yaw_gain is measured.
inline constexpr double kMinYawSpreadDeg = 10.0;

struct TrackEvalResult {
  int frames = 0;
  int lost_frames = 0;
  double vertex_error_mm = 0;             // face region, model space, after rigid alignment; mean over frames
  double vertex_error_similarity_mm = 0;  // the same after a similarity alignment (scale removed)
  double rotation_error_deg = 0;          // mean over frames
  // Slope of the fitted yaw against the true yaw over the frames (least
  // squares with an intercept): 1 when head turns are measured at their size,
  // above 1 when the fit exaggerates them. 0 when the truth turns less than
  // kMinYawSpreadDeg (no slope to measure).
  double yaw_gain = 0;
  double translation_error_cm = 0;
  double focal = 0, focal_true = 0;
  double focal_error_rel = 0;
  double weights_mae = 0;   // mean |w - w_true| over frames and the 53 weights
  double eye_look_mae = 0;  // the same over the eight eyeLook weights (eye_look.hpp)
  // The FACS action units read off the weights (action_units.hpp), by the
  // measures AU benchmarks use: mean |intensity - true intensity| (0-5) over
  // frames and units; the Pearson correlation of each unit's intensity with
  // the truth's over the frames, averaged over the units whose true intensity
  // varies (standard deviation at least kActionUnitMovesFrom; how many in
  // action_units_moving); and the F1 score of the presence calls over every
  // (frame, unit), which calling no unit present scores 0.
  double action_units_mae = 0;
  double action_units_correlation = 0;
  int action_units_moving = 0;
  double action_units_f1 = 0;
  double jitter_mm = 0;         // RMS frame-to-frame motion of the face shape (model space), still head
  double jitter_camera_mm = 0;  // the same in camera space (adds pose jitter, mostly depth)
  double identity_error = 0;    // ||a - a_true|| over the fitted modes
  // Size of the fitted neutral face over the true one (the scale of the
  // similarity that best maps the true face region onto it): 1 when the size,
  // which landmarks hardly show, is right.
  double size_ratio = 0;
  double size_factor = 1;      // the size correction the tracker applied (identity_size.hpp)
  double effective_modes = 0;  // identity directions the landmarks determined (of 50)
  // The neutral face region's error, RMS over vertices in mm (both centred, no
  // rotation), in all and with the size taken out (least-squares scale)...
  double identity_shape_rms_mm = 0;
  double identity_shape_rms_fixed_size_mm = 0;
  // ...and what the identity solve's posterior predicts for them
  // (shape_uncertainty.hpp): equal on average when the fit's noise model and
  // prior are the truth's.
  double shape_sd_mm = 0;
  double shape_sd_fixed_size_mm = 0;
  double fit_ms_per_frame = 0;
  // Gaze: the iris centres against the true ones (SynthRenderer::iris_centre;
  // median, pixels; and the mean of found minus true, x right and y down,
  // pixels), the share of open eyes (frames not mid-blink) where an iris was
  // found, and the mean angle between the estimated and the true
  // head-relative gaze over the frames that have one, and its mean signed
  // part: estimated minus true (yaw, pitch), head-relative, degrees
  // (gaze_angles_deg).
  double iris_error_px = 0;
  Vec2d iris_bias_px = Vec2d::Zero();
  double iris_found = 0;
  double gaze_error_deg = 0;
  Vec2d gaze_bias_deg = Vec2d::Zero();
  int gaze_frames = 0;
};

TrackEvalResult evaluate_track_synthetic(const FaceModel& model, const TrackEvalOptions& options);

// `fit` for the synthetic truth's landmarks: they follow the model's own
// landmark definition (the jaw landmarks are the marched silhouette
// vertices, where a dlib run slides along the outline instead), and there
// is no detector-convention offset for the identity solve to allow for.
CoarseFitOptions fit_options_for_true_landmarks(CoarseFitOptions fit);

struct VideoEvalResult {
  int frames = 0;
  int lost_frames = 0;
  double landmark_nme = 0;  // median over tracked frames of the fit's NME against the detected landmarks
  double landmark_nme_mean = 0;
  double landmark_nme_p90 = 0;
  double focal = 0;
  int gaze_frames = 0;  // tracked frames with an iris found (gaze.hpp); no gaze truth exists for real footage
  CaptureSummary summary;
};

VideoEvalResult evaluate_track_video(const FaceModel& model, const std::string& path, const CaptureOptions& options);

}  // namespace facecap
