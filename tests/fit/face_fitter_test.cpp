#include "facecap/fit/face_fitter.hpp"

#include <gtest/gtest.h>

#include <random>

#include "facecap/model/eye_look.hpp"

#include "facecap/synth/synth_renderer.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {
// Fit options for a synthetic performance seen through its true camera, with
// the truth's own jaw definition.
CoarseFitOptions known_camera(const SynthPerformance& perf) {
  CoarseFitOptions o;
  o.jaw = JawCorrespondence::kMarch;
  o.focal_known = true;
  o.focal_guess = perf.camera.focal;
  return o;
}
}  // namespace

// With the true identity and focal, noise-free landmarks and a weak
// expression prior (so that the optimum is the truth), one frame's pose and
// expression come back from a cold start (initialize_frame + fit_frame).
TEST(FaceFitter, RecoversPoseAndExpressionFromPerfectLandmarks) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions so;
  so.frames = 12;
  so.seed = 4;
  const SynthPerformance perf = make_performance(*model, so);
  const SynthRenderer renderer(*model, perf);
  CoarseFitOptions o = known_camera(perf);
  o.weights.sigma_expression = 5.0;
  const FaceFitter fitter(*model, o, so.width, so.height);
  const Eigen::VectorXd identity = perf.identity.head(fitter.identity_modes()).cast<double>();
  for (const SynthFrame& f : perf.frames) {
    const Landmarks lm = renderer.landmarks(f);
    FrameParameters params(fitter.num_expressions());
    fitter.initialize_frame(lm, identity, perf.camera.focal, params);
    const FrameFitReport report = fitter.fit_frame(lm, identity, perf.camera.focal, nullptr, params);
    EXPECT_LT(rotation_angle_deg(params.pose().rotation_matrix(), f.pose.rotation_matrix()), 0.1)
        << "frame " << f.index;
    EXPECT_LT((params.expression().cast<float>() - f.expression).cwiseAbs().mean(), 0.01f) << "frame " << f.index;
    EXPECT_LT(report.landmark_error, 0.001) << "frame " << f.index;
    EXPECT_GE(params.expression().minCoeff(), 0.0);
    EXPECT_LE(params.expression().maxCoeff(), 1.0);
  }
}

TEST(FaceFitter, JawSlidesAlongTheOutlineOnlyAcrossIt) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions so;
  so.frames = 1;
  so.max_yaw_deg = 0;
  const SynthPerformance perf = make_performance(*model, so);
  const SynthRenderer renderer(*model, perf);
  CoarseFitOptions o;
  o.focal_known = true;
  o.focal_guess = perf.camera.focal;
  const FaceFitter fitter(*model, o, so.width, so.height);
  const Eigen::VectorXd identity = perf.identity.head(fitter.identity_modes()).cast<double>();
  FrameParameters truth(fitter.num_expressions());
  truth.set_pose(perf.frames[0].pose);
  truth.expression() = perf.frames[0].expression.cast<double>();
  // Move a jaw landmark along the jaw (toward the next one): sliding absorbs it.
  Landmarks lm = renderer.landmarks(perf.frames[0]);
  lm[3] += 0.4f * (lm[4] - lm[3]);
  const Landmarks fitted = fitter.project(truth, identity, perf.camera.focal, lm);
  EXPECT_LT((fitted[3] - lm[3]).norm(), 1.5f);
}

// The synthetic lids follow the gaze by eye_look.hpp's convention. With
// noisy landmarks the lids alone say little of where the eyes look; the
// irises at their true places pull the eight eyeLook weights toward the truth.
// A cue that swapped left and right, or up and down, would push them away.
TEST(FaceFitter, TheIrisesGazePullsTheEyeLookWeightsTowardIt) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions so;
  so.frames = 24;
  so.seed = 3;
  const SynthPerformance perf = make_performance(*model, so);
  const SynthRenderer renderer(*model, perf);
  const FaceFitter fitter(*model, known_camera(perf), so.width, so.height);
  const Eigen::VectorXd identity = perf.identity.head(fitter.identity_modes()).cast<double>();
  const EyeballGeometry eyes = eyeball_geometry(*model, identity);
  const std::vector<int> eye_look = EyeLookShapes(*model).indices();
  ASSERT_EQ(eye_look.size(), 8u);
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0f, 3.0f);
  double error_without = 0, error_with = 0, gaze_seen = 0;
  for (const SynthFrame& f : perf.frames) {
    Landmarks lm = renderer.landmarks(f);
    for (Vec2f& p : lm) p += Vec2f(noise(rng), noise(rng));
    const GazeCue cue{&eyes, {renderer.iris_centre(f, 0), renderer.iris_centre(f, 1)}};
    auto eye_look_error = [&](const GazeCue* gaze) {
      FrameParameters params(fitter.num_expressions());
      fitter.initialize_frame(lm, identity, perf.camera.focal, params);
      fitter.fit_frame(lm, identity, perf.camera.focal, nullptr, params, gaze);
      double e = 0;
      for (int k : eye_look) e += std::abs(params.expression()[k] - f.expression[k]) / eye_look.size();
      return e;
    };
    error_without += eye_look_error(nullptr) / so.frames;
    error_with += eye_look_error(&cue) / so.frames;
    gaze_seen += f.gaze_deg.norm() / so.frames;
  }
  EXPECT_GT(gaze_seen, 5.0);  // the eyes do look around
  EXPECT_LT(error_with, 0.6 * error_without) << error_with << " " << error_without;
}

}  // namespace facecap
