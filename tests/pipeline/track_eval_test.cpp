// The coarse tracker against ground truth, with the bars of the tracking
// issue where they hold (see the note on issue 3 for the ones that do not).
#include "facecap/pipeline/track_eval.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_support.hpp"

namespace facecap {

namespace {

// A 1280x720 synthetic sweep fitted from the true landmarks with 1 px of
// noise; 90 frames are a full +-30 degree yaw sweep.
TrackEvalOptions sweep(uint64_t seed, int frames = 90, int still_frames = 30) {
  TrackEvalOptions o;
  o.frames = frames;
  o.seed = seed;
  o.synth.width = 1280;
  o.synth.height = 720;
  o.landmark_noise_px = 1.0;
  o.still_frames = still_frames;
  o.capture.quiet = true;
  return o;
}

TrackEvalResult synthetic(const FaceModel& model, uint64_t seed, int still_frames = 30) {
  return evaluate_track_synthetic(model, sweep(seed, 90, still_frames));
}

}  // namespace

// One test per seed, so that the suite runs them side by side (each some
// 30 s alone, the suite's longest).
class TrueLandmarks : public ::testing::TestWithParam<uint64_t> {};

TEST_P(TrueLandmarks, WithNoiseGivePoseFocalAndSteadyShape) {
  FACECAP_REQUIRE_MODEL(model);
  const uint64_t seed = GetParam();
  const TrackEvalResult r = synthetic(*model, seed);
  EXPECT_EQ(r.frames, 90);
  EXPECT_EQ(r.lost_frames, 0);
  EXPECT_LE(r.rotation_error_deg, 1.0) << "seed " << seed;
  // Head turns at their true size (0.98-1.02 on seeds 1-4). dlib's
  // landmarks on the same renders give 0.90-1.18 (README); this guards the
  // fit itself against such a bias.
  EXPECT_NEAR(r.yaw_gain, 1.0, 0.05) << "seed " << seed;
  EXPECT_LE(r.focal_error_rel, 0.10) << "seed " << seed;
  EXPECT_LE(r.jitter_mm, 0.2) << "seed " << seed;
  // The face's size, which landmarks hardly show (identity_size.hpp): the
  // identity solve's own optimum made these faces 0.979 and 0.970 of their
  // true size (0.957-0.994 on seeds 1-12); corrected, 1.002 and 0.992
  // (0.980-1.018).
  EXPECT_NEAR(r.size_ratio, 1.0, 0.015) << "seed " << seed;
  // The bar of 1.0 mm after a rigid alignment is met on some seeds
  // only (seeds 1-8: 0.98-1.67 mm since the renders' lids follow the gaze;
  // seeds 1-12 before: 0.96-1.86 mm, 1.3-3.5 mm without the size correction):
  // the size's remaining scatter, 1 % of which is 0.76 mm, and the shape
  // itself (after a similarity alignment, 0.68-1.43 mm).
  EXPECT_LE(r.vertex_error_mm, 1.6) << "seed " << seed;
  EXPECT_LE(r.vertex_error_similarity_mm, 1.5) << "seed " << seed;
  EXPECT_LE(r.weights_mae, 0.06) << "seed " << seed;
  // The FACS action units read off the weights (action_units.hpp): seeds
  // 1 / 2, mean intensity error 0.24 / 0.17 (of 0-5; calling every unit
  // absent would score 0.30 on seed 1, whose units move little), each
  // moving unit's correlation with the truth 0.90 / 0.92 on average, F1 of
  // the presence calls 0.76 / 0.78 (0 for calling none).
  EXPECT_LE(r.action_units_mae, 0.3) << "seed " << seed;
  EXPECT_GE(r.action_units_moving, 5) << "seed " << seed;
  EXPECT_GE(r.action_units_correlation, 0.85) << "seed " << seed;
  EXPECT_GE(r.action_units_f1, 0.7) << "seed " << seed;
  // Gaze (gaze.hpp): the renders' eyeballs turn by up to 30 degrees, which
  // ICT's eyeLook shapes do not show, so only the irises can tell. Seeds
  // 1-8: iris centres 1.15-2.13 px from the truth (median; 1.65 and 1.19
  // on seeds 1 and 2; 1.75 and 1.15 since the renders light the iris flat
  // and the truth is the painted ring's centre, synth_renderer.hpp), an
  // iris in 97-100 % of the open eyes, mean gaze
  // error 2.3-6.8 degrees (6.8 and 2.3), worst where the head is turned
  // 20-30 degrees and the iris sits against the dark inner corner of the
  // eye. The gaze's pull on the eight eyeLook weights (face_fitter.hpp)
  // took their mean error from 0.066 and 0.045 to 0.056 and 0.036.
  EXPECT_GE(r.iris_found, 0.95) << "seed " << seed;
  EXPECT_LE(r.iris_error_px, 2.0) << "seed " << seed;
  EXPECT_GE(r.gaze_frames, 80) << "seed " << seed;
  EXPECT_LE(r.gaze_error_deg, 8.0) << "seed " << seed;
  // Its signed part, estimated minus true (yaw, pitch): (4.96, -3.34) and
  // (0.31, -2.01) degrees on seeds 1 and 2 (seeds 5, 6: (-1.0, -3.5),
  // (-1.0, 1.3)); the iris centres sit 0.3-1.6 px below the truth on
  // seeds 1-8 (60 frames; README: "the error's signed part"). An eyeball
  // centre 1 mm off in the fitted head would move the gaze by about 5.5
  // degrees the other way.
  EXPECT_LE(std::abs(r.gaze_bias_deg.x()), 6.0) << "seed " << seed;
  EXPECT_LE(std::abs(r.gaze_bias_deg.y()), 6.0) << "seed " << seed;
  EXPECT_LE(r.eye_look_mae, 0.06) << "seed " << seed;
}

INSTANTIATE_TEST_SUITE_P(TrackEval, TrueLandmarks, ::testing::Values(1u, 2u),
                         [](const ::testing::TestParamInfo<uint64_t>& seed) {
                           return "Seed" + std::to_string(seed.param);
                         });

// `eval track --true-identity --true-focal` holds the identity and the focal
// length at the truth, so that the vertex error is the expressions' and the
// pose's alone (0.27-0.33 mm on seeds 1-4 over 90 frames from the true
// landmarks; 1.9-2.7 mm from dlib's on the renders, docs/open-bars.md).
// Held, they must come out exactly as given, with no size correction.
TEST(TrackEval, TheTrueIdentityHeldLeavesTheExpressionsAndThePoseTheirOwnError) {
  FACECAP_REQUIRE_MODEL(model);
  TrackEvalOptions o = sweep(2, 30, 0);
  o.capture.gaze = false;
  o.true_identity = true;
  o.true_focal = true;
  const TrackEvalResult r = evaluate_track_synthetic(*model, o);
  EXPECT_EQ(r.lost_frames, 0);
  EXPECT_EQ(r.focal, r.focal_true);
  EXPECT_EQ(r.identity_error, 0.0);
  EXPECT_EQ(r.size_factor, 1.0);
  EXPECT_NEAR(r.size_ratio, 1.0, 1e-5);
  EXPECT_LE(r.vertex_error_mm, 0.5);
  EXPECT_LE(r.rotation_error_deg, 0.5);
}

// Smoothing (coarse_tracker.hpp): each frame tied to the next one's fit as
// well as the previous one's. Seed 7, the sweep with the largest still-head
// jitter (the gaze left out, for speed): jitter 0.205 -> 0.156 mm, weights'
// error 0.0645 -> 0.0639, rotation error 0.850 -> 0.838 degrees, rigid vertex
// error 2.023 -> 2.015 mm.
TEST(TrackEval, SmoothingSteadiesAStillHeadWithoutLaggingAMovingOne) {
  FACECAP_REQUIRE_MODEL(model);
  TrackEvalOptions o = sweep(7);
  o.capture.gaze = false;
  o.capture.fit.smooth_frames = 0;
  const TrackEvalResult forward = evaluate_track_synthetic(*model, o);
  o.capture.fit.smooth_frames = 8;
  const TrackEvalResult smoothed = evaluate_track_synthetic(*model, o);
  EXPECT_LE(smoothed.jitter_mm, 0.8 * forward.jitter_mm);
  EXPECT_LE(smoothed.jitter_mm, 0.2);
  EXPECT_LE(smoothed.weights_mae, forward.weights_mae);
  EXPECT_LE(smoothed.rotation_error_deg, forward.rotation_error_deg);
  EXPECT_LE(smoothed.vertex_error_mm, forward.vertex_error_mm);
  EXPECT_EQ(smoothed.lost_frames, 0);
}

// Seed 6 looks down and aside in the identity solve's first frames. Unless
// the gaze pulls the eyeLook weights there too (coarse_tracker.hpp), its lids
// are explained by the face's shape and pose: rotation error 1.15 degrees
// without any pull, 1.14 with the per-frame pull alone, 0.92 with both.
TEST(TrackEval, TheIdentitySolveTakesTheGazesLidsForLidsNotHeadPose) {
  FACECAP_REQUIRE_MODEL(model);
  const TrackEvalResult r = synthetic(*model, 6, 0);
  EXPECT_LE(r.rotation_error_deg, 1.0);
  EXPECT_LE(r.eye_look_mae, 0.07);  // 0.062; 0.077 without the pull in the identity solve, 0.096 with none
}

TEST(TrackEval, RealFootageIsExplainedByTheModel) {
  FACECAP_REQUIRE_MODEL(model);
  struct Clip {
    const char* name;
    bool must_not_lose;
    int min_gaze_frames;  // of 60: frames with an iris found
  };
  // Gaze in the first 60 frames: 60, 57, 60, 60 on the first four; on the
  // last the woman's eyes are nearly shut and look down (dlib marks their
  // openings 0.11-0.17 of their width), where finding no iris is right.
  for (const Clip& clip : {Clip{"address_720p_a.mp4", true, 54}, Clip{"address_720p_b.mp4", true, 51},
                           Clip{"talking_webcam_400x300.mp4", true, 54}, Clip{"talking_webcam2_400x300.mp4", true, 54},
                           Clip{"emotions_pexels_640x360.mp4", false, 0}}) {
    FACECAP_REQUIRE_DATA(video, clip.name);
    CaptureOptions o;
    o.quiet = true;
    o.max_frames = 60;
    const VideoEvalResult r = evaluate_track_video(*model, video.string(), o);
    EXPECT_EQ(r.frames, 60) << clip.name;
    EXPECT_LE(r.landmark_nme, 0.04) << clip.name;
    if (clip.must_not_lose) {
      EXPECT_EQ(r.lost_frames, 0) << clip.name;
    }
    EXPECT_GE(r.gaze_frames, clip.min_gaze_frames) << clip.name;
    // A plausible face: the identity stays within the model's prior
    // (a 50-mode N(0, 1) vector has norm about 7).
    EXPECT_LT(r.summary.identity.identity.norm(), 12.0) << clip.name;
  }
}

}  // namespace facecap
