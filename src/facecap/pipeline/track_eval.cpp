#include "facecap/pipeline/track_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "facecap/core/geometry.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/core/rigid_alignment.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/expr/action_units.hpp"
#include "facecap/fit/gaze.hpp"
#include "facecap/fit/identity_size.hpp"
#include "facecap/fit/shape_uncertainty.hpp"
#include "facecap/model/eye_look.hpp"
#include "facecap/synth/synth_renderer.hpp"
#include "facecap/synth/synthesize.hpp"

namespace facecap {

namespace {

// Fits a synthetic performance; returns fits in frame order.
std::vector<CoarseFit> fit_performance(const FaceModel& model, const SynthPerformance& perf, const TrackEvalOptions& o,
                                       IdentityEstimate& identity, double& fit_ms) {
  std::vector<CoarseFit> fits;
  if (o.landmarks == LandmarkSource::kTruth) {
    const SynthRenderer renderer(model, perf);
    CoarseTracker tracker(model, fit_options_for_true_landmarks(o.capture.fit), perf.options.width,
                          perf.options.height);
    std::mt19937_64 rng(perf.options.seed * 31 + 7);
    std::normal_distribution<float> noise(0.0f, float(o.landmark_noise_px));
    // The irises are found on the rendered frames inside the same noisy landmarks.
    std::mt19937_64 image_noise(perf.options.seed * 131 + 3);
    double ms = 0;
    for (const SynthFrame& f : perf.frames) {
      Landmarks lm = renderer.landmarks(f);
      for (Vec2f& p : lm) p += Vec2f(noise(rng), noise(rng));
      IrisSearch search;
      if (o.capture.gaze) {
        cv::Mat grey;
        cv::cvtColor(renderer.render(f, image_noise), grey, cv::COLOR_BGR2GRAY);
        search = iris_search(grey, lm);
      }
      const auto start = std::chrono::steady_clock::now();
      for (CoarseFit& fit : tracker.push(f.index, f.time, lm, std::move(search))) fits.push_back(std::move(fit));
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    const auto start = std::chrono::steady_clock::now();
    for (CoarseFit& fit : tracker.finish()) fits.push_back(std::move(fit));
    fit_ms = ms + std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    identity = tracker.identity();
    return fits;
  }
  // dlib: render the video and run the whole capture pipeline on it.
  TempDir dir("facecap-eval");
  const SynthJobResult job = synthesize(model, perf.options, dir.path(), true);
  auto source = open_input(job.video.string());
  CaptureOptions capture = o.capture;
  capture.quiet = true;
  const CaptureSummary summary = run_capture(model, *source, capture, [&](const CapturedFrame& f) {
    fits.push_back(f.fit);
    fits.back().valid = f.status != TrackStatus::kLost;
  });
  identity = summary.identity;
  fit_ms = summary.timings.fit_ms;
  return fits;
}

// Least-squares slope of y on x (with an intercept); 0 when x spans less
// than kMinYawSpreadDeg.
double regression_slope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2) return 0.0;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  if (*hi - *lo < kMinYawSpreadDeg) return 0.0;
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxy / sxx;
}

// TrackEvalResult's action-unit correlation and F1 from each unit's fitted
// and true intensities over the tracked frames.
void score_action_units(const std::vector<std::vector<double>>& fitted, const std::vector<std::vector<double>>& truth,
                        TrackEvalResult& r) {
  long true_positive = 0, false_positive = 0, false_negative = 0;
  for (size_t u = 0; u < fitted.size(); ++u) {
    if (standard_deviation(truth[u]) >= kActionUnitMovesFrom) {
      r.action_units_correlation += pearson_correlation(fitted[u], truth[u]);
      ++r.action_units_moving;
    }
    for (size_t i = 0; i < fitted[u].size(); ++i) {
      const bool called = fitted[u][i] >= kActionUnitPresentFrom, present = truth[u][i] >= kActionUnitPresentFrom;
      true_positive += called && present;
      false_positive += called && !present;
      false_negative += !called && present;
    }
  }
  if (r.action_units_moving > 0) r.action_units_correlation /= r.action_units_moving;
  const long scored = 2 * true_positive + false_positive + false_negative;
  r.action_units_f1 = scored > 0 ? 2.0 * true_positive / double(scored) : 0.0;
}

Positions fitted_shape(const FaceModel& model, const IdentityEstimate& id, const Eigen::VectorXf& w) {
  return model.evaluate(id.identity.cast<float>(), w, regions::kFace);
}

// RMS distance (mm) between two point sets, each centred on its centroid;
// with `fit_scale`, `fitted` is first scaled about its centroid by the least-
// squares factor (the size taken out).
double centred_rms_mm(const Positions& truth, const Positions& fitted, bool fit_scale) {
  const auto centred = [](const Positions& p) -> Eigen::Matrix3Xd {
    const Eigen::Matrix3Xd d = p.cast<double>();
    return d.colwise() - d.rowwise().mean();
  };
  const Eigen::Matrix3Xd t = centred(truth);
  Eigen::Matrix3Xd f = centred(fitted);
  if (fit_scale && f.squaredNorm() > 0) f *= t.cwiseProduct(f).sum() / f.squaredNorm();
  return 10.0 * std::sqrt((t - f).squaredNorm() / double(std::max<Eigen::Index>(1, t.cols())));
}

}  // namespace

CoarseFitOptions fit_options_for_true_landmarks(CoarseFitOptions fit) {
  fit.jaw = JawCorrespondence::kMarch;
  fit.weights.identity_sigma_factor = 1.0;
  return fit;
}

TrackEvalOptions with_truth_held(const TrackEvalOptions& options, const SynthPerformance& perf) {
  TrackEvalOptions held = options;
  CoarseFitOptions& fit = held.capture.fit;
  if (options.true_focal) {
    fit.focal_known = true;
    fit.focal_guess = perf.camera.focal;
  }
  if (options.true_identity) fit.known_identity = perf.identity.head(fit.identity_modes).cast<double>();
  return held;
}

TrackEvalResult evaluate_track_synthetic(const FaceModel& model, const TrackEvalOptions& options) {
  TrackEvalResult r;
  SynthOptions so = options.synth;
  so.frames = options.frames;
  so.seed = options.seed;
  const SynthPerformance perf = make_performance(model, so);
  IdentityEstimate id;
  double fit_ms = 0;
  const std::vector<CoarseFit> frames = fit_performance(model, perf, with_truth_held(options, perf), id, fit_ms);

  r.focal = id.focal;
  r.focal_true = perf.camera.focal;
  r.focal_error_rel = std::abs(id.focal - perf.camera.focal) / perf.camera.focal;
  r.identity_error = (id.identity - perf.identity.head(id.identity.size()).cast<double>()).norm();
  r.size_factor = id.size_factor;
  r.effective_modes = id.effective_modes;
  const Positions true_neutral = model.evaluate(perf.identity, Eigen::VectorXf(), regions::kFace);
  const Positions fitted_neutral = fitted_shape(model, id, Eigen::VectorXf());
  r.size_ratio = align_rigid(true_neutral, fitted_neutral, true).scale;
  r.identity_shape_rms_mm = centred_rms_mm(true_neutral, fitted_neutral, false);
  r.identity_shape_rms_fixed_size_mm = centred_rms_mm(true_neutral, fitted_neutral, true);
  const ShapeUncertainty uncertainty(model, static_cast<int>(id.identity.size()));
  const IdentitySizeCorrection size(model, static_cast<int>(id.identity.size()));
  r.shape_sd_mm = uncertainty.rms_mm(id.covariance);
  r.shape_sd_fixed_size_mm = uncertainty.fixed_size_rms_mm(id.covariance, id.identity + size.mean_coefficients());
  int valid = 0;
  std::vector<double> true_yaw, fitted_yaw;
  const SynthRenderer renderer(model, perf);
  std::vector<double> iris_errors;
  int open_eyes = 0, found_open = 0, gaze_frames = 0;
  const std::vector<int> eye_look = EyeLookShapes(model).indices();
  const ActionUnitReader action_units(model.expression_names);
  std::vector<std::vector<double>> unit_fitted(action_units.size()), unit_true(action_units.size());
  for (const CoarseFit& fit : frames) {
    ++r.frames;
    if (!fit.valid) {
      ++r.lost_frames;
      continue;
    }
    ++valid;
    const SynthFrame& truth = perf.frames[fit.index];
    const Positions true_shape = model.evaluate(perf.identity, truth.expression, regions::kFace);
    const Positions fitted = fitted_shape(model, id, fit.expression);
    r.vertex_error_mm += 10.0 * aligned_mean_distance(fitted, true_shape);
    r.vertex_error_similarity_mm += 10.0 * aligned_mean_distance(fitted, true_shape, true);
    r.rotation_error_deg += rotation_angle_deg(fit.pose.rotation_matrix(), truth.pose.rotation_matrix());
    true_yaw.push_back(yaw_pitch_roll_deg(truth.pose.rotation_matrix()).x());
    fitted_yaw.push_back(yaw_pitch_roll_deg(fit.pose.rotation_matrix()).x());
    r.translation_error_cm += (fit.pose.translation - truth.pose.translation).norm();
    r.weights_mae += (fit.expression - truth.expression).cwiseAbs().mean();
    for (int k : eye_look) r.eye_look_mae += std::abs(fit.expression[k] - truth.expression[k]) / eye_look.size();
    const Eigen::VectorXd units = action_units.intensities(fit.expression);
    const Eigen::VectorXd true_units = action_units.intensities(truth.expression);
    r.action_units_mae += (units - true_units).cwiseAbs().mean();
    for (int u = 0; u < action_units.size(); ++u) {
      unit_fitted[u].push_back(units[u]);
      unit_true[u].push_back(true_units[u]);
    }
    if (!options.capture.gaze) continue;
    const float blink = std::max(truth.expression[model.expression_index("eyeBlink_L")],
                                 truth.expression[model.expression_index("eyeBlink_R")]);
    for (int eye = 0; eye < 2; ++eye) {
      if (blink < 0.5f) ++open_eyes;
      if (!fit.irises[eye]) continue;
      const Vec2d iris_error = fit.irises[eye]->centre - renderer.iris_centre(truth, eye);
      iris_errors.push_back(iris_error.norm());
      r.iris_bias_px += iris_error;
      if (blink < 0.5f) ++found_open;
    }
    if (fit.gaze.valid()) {
      ++gaze_frames;
      const Vec3d true_gaze = turned_axis(renderer.eyeballs(), 0, truth.gaze_deg.x(), truth.gaze_deg.y()) +
                              turned_axis(renderer.eyeballs(), 1, truth.gaze_deg.x(), truth.gaze_deg.y());
      r.gaze_error_deg += angle_between_deg(true_gaze, fit.gaze.direction());
      r.gaze_bias_deg += fit.gaze.angles_deg() - gaze_angles_deg(true_gaze);
    }
  }
  if (gaze_frames > 0) {
    r.gaze_error_deg /= gaze_frames;
    r.gaze_bias_deg /= gaze_frames;
  }
  r.gaze_frames = gaze_frames;
  r.iris_error_px = median(iris_errors);
  if (!iris_errors.empty()) r.iris_bias_px /= static_cast<double>(iris_errors.size());
  r.iris_found = open_eyes > 0 ? double(found_open) / open_eyes : 0.0;
  if (valid > 0) {
    r.vertex_error_mm /= valid;
    r.vertex_error_similarity_mm /= valid;
    r.rotation_error_deg /= valid;
    r.translation_error_cm /= valid;
    r.weights_mae /= valid;
    r.eye_look_mae /= valid;
    r.action_units_mae /= valid;
  }
  r.yaw_gain = regression_slope(true_yaw, fitted_yaw);
  score_action_units(unit_fitted, unit_true, r);
  r.fit_ms_per_frame = r.frames > 0 ? fit_ms / r.frames : 0.0;

  if (options.still_frames > 1) {
    SynthOptions still = so;
    still.frames = options.still_frames;
    still.still = true;
    const SynthPerformance still_perf = make_performance(model, still);
    TrackEvalOptions so2 = options;
    so2.still_frames = 0;
    IdentityEstimate still_id;
    double ms = 0;
    so2.capture.gaze = false;
    const std::vector<CoarseFit> still_fits = fit_performance(model, still_perf, so2, still_id, ms);
    double shape_sq = 0, camera_sq = 0;
    long count = 0;
    std::optional<Positions> previous_shape, previous_camera;
    for (const CoarseFit& fit : still_fits) {
      if (!fit.valid) {
        previous_shape.reset();
        continue;
      }
      const Positions shape = fitted_shape(model, still_id, fit.expression);
      const Positions cam = to_camera(shape, fit.pose);
      if (previous_shape) {
        shape_sq += (shape - *previous_shape).colwise().squaredNorm().sum();
        camera_sq += (cam - *previous_camera).colwise().squaredNorm().sum();
        count += cam.cols();
      }
      previous_shape = shape;
      previous_camera = cam;
    }
    r.jitter_mm = count > 0 ? 10.0 * std::sqrt(shape_sq / count) : 0.0;
    r.jitter_camera_mm = count > 0 ? 10.0 * std::sqrt(camera_sq / count) : 0.0;
  }
  return r;
}

VideoEvalResult evaluate_track_video(const FaceModel& model, const std::string& path, const CaptureOptions& options) {
  VideoEvalResult r;
  auto source = open_input(path);
  std::vector<double> nme;
  r.summary = run_capture(model, *source, options, [&](const CapturedFrame& f) {
    if (f.status != TrackStatus::kLost) nme.push_back(f.fit.landmark_error);
    r.gaze_frames += f.fit.gaze.valid();
  });
  r.frames = r.summary.frames;
  r.lost_frames = r.summary.lost;
  r.focal = r.summary.identity.focal;
  if (!nme.empty()) {
    std::sort(nme.begin(), nme.end());
    r.landmark_nme = nme[nme.size() / 2];
    r.landmark_nme_p90 = nme[std::min(nme.size() - 1, nme.size() * 9 / 10)];
    for (double v : nme) r.landmark_nme_mean += v / nme.size();
  }
  return r;
}

}  // namespace facecap
