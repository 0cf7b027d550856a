#include "facecap/fit/coarse_tracker.hpp"

#include <gtest/gtest.h>

#include <random>

#include "facecap/synth/synth_renderer.hpp"
#include "test_support.hpp"

namespace facecap {
namespace {

// A synthetic performance of `frames` frames and its renderer, whose
// landmarks are the truth.
struct SyntheticTake {
  SyntheticTake(const FaceModel& model, int frames)
      : options(with_frames(frames)), perf(make_performance(model, options)), renderer(model, perf) {}
  static SynthOptions with_frames(int frames) {
    SynthOptions o;
    o.frames = frames;
    return o;
  }
  const SynthOptions options;
  const SynthPerformance perf;
  const SynthRenderer renderer;
};

}  // namespace

TEST(CoarseTracker, RejectsLandmarksNoFaceCanExplainAndRecovers) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 40);
  CoarseFitOptions o;
  o.init_frames = 10;
  CoarseTracker tracker(*model, o, take.options.width, take.options.height);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(100, 400);
  std::vector<CoarseFit> fits;
  for (const SynthFrame& f : take.perf.frames) {
    std::optional<Landmarks> lm = take.renderer.landmarks(f);
    if (f.index == 20) {
      for (Vec2f& p : *lm) p = Vec2f(u(rng), u(rng));  // a detector failure: scattered points
    }
    if (f.index == 25) lm.reset();  // no face
    for (CoarseFit& fit : tracker.push(f.index, f.time, lm)) fits.push_back(std::move(fit));
  }
  for (CoarseFit& fit : tracker.finish()) fits.push_back(std::move(fit));
  ASSERT_EQ(fits.size(), 40u);
  for (const CoarseFit& fit : fits) {
    EXPECT_EQ(fit.index, &fit - fits.data());  // in order
    if (fit.index == 20 || fit.index == 25) {
      EXPECT_FALSE(fit.valid) << "frame " << fit.index;
    } else {
      EXPECT_TRUE(fit.valid) << "frame " << fit.index;
      EXPECT_TRUE(fit.expression.allFinite());
      EXPECT_LT(fit.landmark_error, 0.02) << "frame " << fit.index;
    }
  }
  EXPECT_TRUE(tracker.initialized());
  EXPECT_EQ(tracker.identity().frames_used, 10);
}

// With smoothing, fits come out in blocks of smooth_frames, each frame once
// and in order, none held longer than a block and the frame after it, and a
// frame without a face ends the block before it at once.
TEST(CoarseTracker, SmoothedFitsComeOutInOrderAtMostABlockLate) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 40);
  CoarseFitOptions o;
  o.init_frames = 10;
  o.smooth_frames = 8;
  CoarseTracker tracker(*model, o, take.options.width, take.options.height);
  std::vector<CoarseFit> fits;
  for (const SynthFrame& f : take.perf.frames) {
    std::optional<Landmarks> lm = take.renderer.landmarks(f);
    if (f.index == 23) lm.reset();  // no face
    for (CoarseFit& fit : tracker.push(f.index, f.time, lm)) fits.push_back(std::move(fit));
    if (f.index >= o.init_frames - 1) {
      ASSERT_FALSE(fits.empty()) << f.index;
      EXPECT_GE(fits.back().index, f.index - o.smooth_frames) << f.index;
    }
    if (f.index == 23) {
      EXPECT_EQ(fits.back().index, 23);  // the frames before it are out
    }
  }
  for (CoarseFit& fit : tracker.finish()) fits.push_back(std::move(fit));
  ASSERT_EQ(fits.size(), 40u);
  for (const CoarseFit& fit : fits) {
    EXPECT_EQ(fit.index, &fit - fits.data());
    EXPECT_EQ(fit.valid, fit.index != 23) << fit.index;
    if (fit.valid) {
      EXPECT_LT(fit.landmark_error, 0.02) << "frame " << fit.index;
    }
  }
}

// The identity solve weighs its landmarks as identity_evidence_frames
// frames' however many frames it has: a detector's systematic error repeats
// in every frame, so repeating frames must not move the identity.
TEST(CoarseTracker, RepeatedFramesAddNoEvidenceAboutTheIdentity) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 40);
  auto solve = [&](int copies) {
    CoarseFitOptions o;
    o.init_frames = take.options.frames * copies;
    CoarseTracker tracker(*model, o, take.options.width, take.options.height);
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    int index = 0;
    for (const SynthFrame& f : take.perf.frames) {
      Landmarks lm = take.renderer.landmarks(f);
      for (Vec2f& p : lm) p += Vec2f(noise(rng), noise(rng));
      for (int c = 0; c < copies; ++c) tracker.push(index++, f.time, lm);
    }
    tracker.finish();
    EXPECT_EQ(tracker.identity().frames_used, take.options.frames * copies);
    return tracker.identity();
  };
  const IdentityEstimate once = solve(1), thrice = solve(3);
  EXPECT_GT(once.identity.norm(), 1.0);
  EXPECT_LT((once.identity - thrice.identity).norm(), 0.02 * once.identity.norm());
  EXPECT_NEAR(once.focal, thrice.focal, 1e-3 * once.focal);
}

TEST(CoarseTracker, ShortInputsAreSolvedAtTheEnd) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 5);
  CoarseTracker tracker(*model, CoarseFitOptions{}, take.options.width, take.options.height);  // wants 30 frames
  for (const SynthFrame& f : take.perf.frames)
    EXPECT_TRUE(tracker.push(f.index, f.time, take.renderer.landmarks(f)).empty());
  const std::vector<CoarseFit> fits = tracker.finish();
  ASSERT_EQ(fits.size(), 5u);
  for (const CoarseFit& fit : fits) EXPECT_TRUE(fit.valid);
  EXPECT_EQ(tracker.identity().frames_used, 5);
}

// A face seen in a few frames and then gone holds the frames after it only
// for init_patience frames: then the identity is solved from what there is
// and the frames go (a still lost one at once), not at the input's end.
TEST(CoarseTracker, AFaceSeenBrieflyHoldsLaterFramesOnlySoLong) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 4);
  CoarseFitOptions o;
  o.init_patience = 20;
  CoarseTracker tracker(*model, o, take.options.width, take.options.height);  // wants 30 frames with a face
  for (const SynthFrame& f : take.perf.frames)
    EXPECT_TRUE(tracker.push(f.index, f.time, take.renderer.landmarks(f)).empty());
  for (int i = 4; i < 23; ++i) EXPECT_TRUE(tracker.push(i, i / 30.0, std::nullopt).empty()) << i;
  const std::vector<CoarseFit> fits = tracker.push(23, 23 / 30.0, std::nullopt);  // the 20th without a face
  ASSERT_EQ(fits.size(), 24u);
  for (const CoarseFit& fit : fits) EXPECT_EQ(fit.valid, fit.index < 4) << fit.index;
  EXPECT_TRUE(tracker.initialized());
  EXPECT_EQ(tracker.identity().frames_used, 4);
  const std::vector<CoarseFit> next = tracker.push(24, 24 / 30.0, std::nullopt);
  ASSERT_EQ(next.size(), 1u);
  EXPECT_FALSE(next[0].valid);

  // With no face at all the frames go as lost, and the solve waits for one.
  CoarseTracker empty(*model, o, take.options.width, take.options.height);
  for (int i = 0; i < 19; ++i) EXPECT_TRUE(empty.push(i, i / 30.0, std::nullopt).empty()) << i;
  EXPECT_EQ(empty.push(19, 19 / 30.0, std::nullopt).size(), 20u);
  EXPECT_FALSE(empty.initialized());
}

// A known identity (--identity) is held as given. With the focal length
// known too, nothing is left to solve over first frames: the first frame
// gives the first fit. Otherwise the focal length is solved over the first
// frames as usual, with the face held.
TEST(CoarseTracker, AKnownIdentityIsHeldAndWithAKnownFocalStartsAtOnce) {
  FACECAP_REQUIRE_MODEL(model);
  const SyntheticTake take(*model, 32);
  CoarseFitOptions o;
  o.init_frames = 30;
  o.smooth_frames = 0;  // each fit as soon as it is done
  o.known_identity = take.perf.identity.head(o.identity_modes).cast<double>();
  o.focal_guess = take.perf.camera.focal;
  o.focal_known = true;
  CoarseTracker at_once(*model, o, take.options.width, take.options.height);
  const std::vector<CoarseFit> first = at_once.push(0, 0.0, take.renderer.landmarks(take.perf.frames[0]));
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(first[0].valid);
  EXPECT_EQ(at_once.identity().identity, *o.known_identity);
  EXPECT_EQ(at_once.identity().frames_used, 1);
  // The true face and lens leave only pose and expression: one frame's fit,
  // with no frames before it, gives the pose to 1.3 degrees.
  const double angle =
      Eigen::AngleAxisd(first[0].pose.rotation_matrix().transpose() * take.perf.frames[0].pose.rotation_matrix())
          .angle();
  EXPECT_LT(angle * 180 / M_PI, 2.0);

  o.focal_known = false;
  o.focal_guess = 0;  // the default guess, 1.0 x the wider side
  CoarseTracker solved_focal(*model, o, take.options.width, take.options.height);
  for (const SynthFrame& f : take.perf.frames) {
    const auto fits = solved_focal.push(f.index, f.time, take.renderer.landmarks(f));
    EXPECT_EQ(fits.empty(), f.index < 29) << f.index;  // the 30th frame starts the output
  }
  EXPECT_EQ(solved_focal.identity().identity, *o.known_identity);
  EXPECT_NEAR(solved_focal.identity().focal / take.perf.camera.focal, 1.0, 0.10);  // issue 3's bar
}

}  // namespace facecap
