#include "facecap/pipeline/photo_identity_eval.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "facecap/core/error.hpp"
#include "facecap/core/rigid_alignment.hpp"
#include "facecap/fit/coarse_tracker.hpp"
#include "facecap/model/eye_look.hpp"
#include "facecap/synth/synth_renderer.hpp"

namespace facecap {

PhotoIdentityEvalResult evaluate_photo_identity_synthetic(const FaceModel& model, const TrackEvalOptions& options,
                                                          int stride) {
  if (stride < 1) throw Error("eval track --photos: the stride must be at least 1");
  SynthOptions so = options.synth;
  so.frames = options.frames;
  so.seed = options.seed;
  const SynthPerformance perf = make_performance(model, so);
  const SynthRenderer renderer(model, perf);
  // As capture fits a still image (capture_session.cpp), from the truth's
  // landmarks.
  CoarseFitOptions fit = fit_options_for_true_landmarks(with_truth_held(options, perf).capture.fit);
  fit.set_single_image();
  std::mt19937_64 rng(perf.options.seed * 31 + 7);
  std::normal_distribution<float> noise(0.0f, float(options.landmark_noise_px));
  const Positions true_neutral = model.evaluate(perf.identity, Eigen::VectorXf(), regions::kFace);

  // The gaze and the blinks are not what a photo's identity confuses with
  // its shape; the expressions' strength leaves them out.
  Eigen::VectorXf counted = Eigen::VectorXf::Ones(model.num_expressions());
  for (const int k : EyeLookShapes(model).indices()) counted[k] = 0;
  for (const char* blink : {"eyeBlink_L", "eyeBlink_R"}) counted[model.expression_index(blink)] = 0;

  struct Photo {
    double strength, shape_error_mm, weights_mae, moved_mae;
  };
  std::vector<Photo> photos;
  for (int f = 0; f < so.frames; f += stride) {
    const SynthFrame& truth = perf.frames[f];
    Landmarks lm = renderer.landmarks(truth);
    for (Vec2f& p : lm) p += Vec2f(noise(rng), noise(rng));
    CoarseTracker tracker(model, fit, so.width, so.height);
    std::vector<CoarseFit> fits = tracker.push(0, 0.0, lm);
    for (CoarseFit& more : tracker.finish()) fits.push_back(std::move(more));
    if (fits.empty() || !fits.front().valid) continue;
    const Eigen::VectorXf& w = fits.front().expression;
    const Positions fitted_neutral =
        model.evaluate(tracker.identity().identity.cast<float>(), Eigen::VectorXf(), regions::kFace);
    Photo p;
    p.strength = truth.expression.cwiseProduct(counted).norm();
    p.shape_error_mm = 10.0 * aligned_mean_distance(fitted_neutral, true_neutral, true);
    p.weights_mae = (w - truth.expression).cwiseAbs().mean();
    const Eigen::ArrayXf moved = (truth.expression.cwiseProduct(counted).array() > 0.1f).cast<float>();
    p.moved_mae = moved.sum() > 0 ? ((w - truth.expression).array().abs() * moved).sum() / moved.sum() : 0.0;
    photos.push_back(p);
  }
  PhotoIdentityEvalResult r;
  r.photos = static_cast<int>(photos.size());
  if (photos.empty()) return r;
  std::sort(photos.begin(), photos.end(), [](const Photo& a, const Photo& b) { return a.strength < b.strength; });
  const size_t half = photos.size() / 2;
  const auto mean = [](auto begin, auto end, double Photo::*field) {
    if (begin == end) return 0.0;
    double sum = 0;
    for (auto it = begin; it != end; ++it) sum += (*it).*field;
    return sum / double(end - begin);
  };
  r.shape_error_mm = mean(photos.begin(), photos.end(), &Photo::shape_error_mm);
  r.shape_error_calm_mm = mean(photos.begin(), photos.begin() + half, &Photo::shape_error_mm);
  r.shape_error_expressive_mm = mean(photos.begin() + half, photos.end(), &Photo::shape_error_mm);
  r.weights_mae = mean(photos.begin(), photos.end(), &Photo::weights_mae);
  r.expression_mae_expressive = mean(photos.begin() + half, photos.end(), &Photo::moved_mae);
  return r;
}

}  // namespace facecap
