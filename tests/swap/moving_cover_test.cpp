// What moves across the face other than the face: found by the optical
// flow against the tracked surface's own motion, carried while it rests,
// and nothing where the face alone moves, or the tracking is a little off.
#include "facecap/swap/moving_cover.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "facecap/core/error.hpp"
#include "facecap/core/uv_texel.hpp"
#include "facecap/swap/face_flow.hpp"
#include "swap/unit_square.hpp"

namespace facecap {

namespace {

using test::largest;
using test::unit_square;

// A flat "face" 12.8 cm square, 60 cm from a 640x480 camera of focal 800
// px: 171 px across, 0.75 mm a pixel; its UV grid 1 mm a texel (128).
constexpr float kHalfCm = 6.4f, kDepthCm = 60.0f;
const PinholeCamera kCamera = PinholeCamera::centered(800.0, 640, 480);

MillimetreGrid grid() { return millimetre_grid(unit_square(), 128.0, 1.0); }

// Grainy texture (grey 60-200), blurred to a few pixels' grain.
cv::Mat grain(int size, int seed) {
  cv::Mat t(size, size, CV_32F);
  cv::RNG(seed).fill(t, cv::RNG::NORMAL, 130.0, 40.0);
  cv::GaussianBlur(t, t, cv::Size(0, 0), 2.0);
  cv::Mat out;
  cv::normalize(t, t, 60, 200, cv::NORM_MINMAX);
  t.convertTo(out, CV_8U);
  return out;
}

// The square's corners (UV (0,0), (1,0), (1,1), (0,1); v up) moved by
// `offset_cm` sideways.
Positions square_points(float offset_cm) {
  Positions p(3, 4);
  p.col(0) = Vec3f(-kHalfCm + offset_cm, kHalfCm, kDepthCm);
  p.col(1) = Vec3f(kHalfCm + offset_cm, kHalfCm, kDepthCm);
  p.col(2) = Vec3f(kHalfCm + offset_cm, -kHalfCm, kDepthCm);
  p.col(3) = Vec3f(-kHalfCm + offset_cm, -kHalfCm, kDepthCm);
  return p;
}

// The frame: the face's texture on the square at `offset_cm`, and a disc
// of its own texture (moving with it) centred at `cover` (pixels) if any.
cv::Mat frame(float offset_cm, std::optional<cv::Point> cover = std::nullopt) {
  static const cv::Mat face = grain(171, 1), hand = grain(240, 2);
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(40, 40, 40));
  const float px_per_cm = float(kCamera.focal) / kDepthCm;
  const cv::Point2f top_left(float(kCamera.cx) + (offset_cm - kHalfCm) * px_per_cm,
                             float(kCamera.cy) - kHalfCm * px_per_cm);
  cv::Mat warp = (cv::Mat_<double>(2, 3) << 1, 0, top_left.x, 0, 1, top_left.y);
  cv::Mat grey(image.size(), CV_8U, cv::Scalar(40));
  cv::warpAffine(face, grey, warp, image.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  if (cover) {
    cv::Mat disc(image.size(), CV_8U, cv::Scalar(0));
    cv::circle(disc, *cover, 55, cv::Scalar(255), cv::FILLED);  // 8 cm: a palm
    cv::Mat moved;
    warp = (cv::Mat_<double>(2, 3) << 1, 0, cover->x - 120, 0, 1, cover->y - 120);
    cv::warpAffine(hand, moved, warp, image.size());
    moved.copyTo(grey, disc);
  }
  cv::cvtColor(grey, image, cv::COLOR_GRAY2BGR);
  return image;
}

// The evidence at an image point of the square at `offset_cm`.
float evidence_at(const cv::Mat& evidence, cv::Point p, float offset_cm) {
  const float px_per_cm = float(kCamera.focal) / kDepthCm;
  const float u = (p.x - float(kCamera.cx) - (offset_cm - kHalfCm) * px_per_cm) / (2 * kHalfCm * px_per_cm);
  const float row = (p.y - float(kCamera.cy) + kHalfCm * px_per_cm) / (2 * kHalfCm * px_per_cm);
  const Vec2f t = uv_to_texel(Vec2f(u, 1.0f - row), evidence.cols);
  const int x = std::clamp(cvRound(t.x()), 0, evidence.cols - 1), y = std::clamp(cvRound(t.y()), 0, evidence.rows - 1);
  return evidence.at<float>(y, x);
}

}  // namespace

TEST(MovingCover, ACoverSlidingAcrossTheFaceIsFoundAndStaysFoundWhileItRests) {
  const MillimetreGrid g = grid();
  MovingCover mover(unit_square(), g);
  const cv::Mat seen(g.map.size, g.map.size, CV_32F, cv::Scalar(1));
  const Positions still = square_points(0);
  EXPECT_EQ(largest(mover.update(frame(0), still, kCamera, seen)), 0.0);  // no last frame
  EXPECT_EQ(largest(mover.update(frame(0), still, kCamera, seen)), 0.0);  // nothing moves
  // In from the left at 12 px (9 mm) a frame, then resting.
  cv::Point cover(180, 250);
  cv::Mat e;
  for (int i = 0; i < 8; ++i) {
    cover.x += 12;
    e = mover.update(frame(0, cover), still, kCamera, seen);
  }
  EXPECT_GT(evidence_at(e, cover, 0), 0.99f);
  EXPECT_EQ(evidence_at(e, {cover.x + 75, cover.y}, 0), 0.0f);  // beside it
  EXPECT_EQ(evidence_at(e, {320, 190}, 0), 0.0f);
  for (int i = 0; i < 24; ++i) e = mover.update(frame(0, cover), still, kCamera, seen);
  const float rested = evidence_at(e, cover, 0);  // half a half-life on
  EXPECT_GT(rested, 0.6f);
  EXPECT_LT(rested, 0.8f);
  // It leaves downward, fast: what it uncovered is no cover.
  for (int i = 0; i < 8; ++i) {
    cover.y += 20;
    e = mover.update(frame(0, cover), still, kCamera, seen);
  }
  EXPECT_LT(evidence_at(e, {cover.x, 250}, 0), 0.5f);
  // After reset() nothing is carried.
  mover.reset();
  EXPECT_EQ(largest(mover.update(frame(0), still, kCamera, seen)), 0.0);
}

TEST(MovingCover, TheFaceMovingOrItsTrackingALittleOffIsNoCover) {
  const MillimetreGrid g = grid();
  MovingCover mover(unit_square(), g);
  const cv::Mat seen(g.map.size, g.map.size, CV_32F, cv::Scalar(1));
  // The face moves 6 px (4.5 mm) a frame and the model with it.
  for (int i = 0; i < 10; ++i) {
    const float offset = 0.45f * i;
    EXPECT_EQ(largest(mover.update(frame(offset), square_points(offset), kCamera, seen)), 0.0) << i;
  }
  // The face moves and the model stays (the tracking 3 mm a frame late):
  // the whole face shares the disagreement.
  mover.reset();
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(largest(mover.update(frame(0.3f * i), square_points(0), kCamera, seen)), 0.0) << i;
  }
}

TEST(FaceFlow, FollowsTheFaceBothWaysAndStartsAgainAcrossAGap) {
  const Positions points = square_points(0);
  const cv::Rect box = facing_box(unit_square(), points, kCamera, {640, 480}, 8);
  FaceFlow flow;
  EXPECT_TRUE(flow.next(frame(0), box, 0).empty());  // no last frame
  // The face 0.45 cm (6 px) to the right.
  const FlowPair pair = flow.next(frame(0.45f), box, 1);
  ASSERT_FALSE(pair.empty());
  EXPECT_EQ(pair.index, 1);
  const Vec2f centre = pair.window(Vec2f(320, 240));
  const cv::Vec2f back = pair.back.at<cv::Vec2f>(cvRound(centre.y()), cvRound(centre.x()));
  const cv::Vec2f ahead = pair.ahead.at<cv::Vec2f>(cvRound(centre.y()), cvRound(centre.x()));
  const float shift = 6.0f * pair.window.scale;
  EXPECT_NEAR(back[0], -shift, 0.3f);
  EXPECT_NEAR(ahead[0], shift, 0.3f);
  EXPECT_NEAR(back[1], 0.0f, 0.3f);
  EXPECT_LE(pair.back.cols, 192);                        // the window scaled to the flow's width
  EXPECT_TRUE(flow.next(frame(0.45f), box, 3).empty());  // frame 2 missing
  EXPECT_FALSE(flow.next(frame(0.45f), box, 4).empty());
  flow.reset();
  EXPECT_TRUE(flow.next(frame(0.45f), box, 5).empty());
  EXPECT_TRUE(flow.next(frame(0.45f), cv::Rect(), 6).empty());  // no face
  EXPECT_THROW(FaceFlow(8), Error);
}

// A skipped frame is still the last frame: the next flows run from it.
TEST(FaceFlow, AfterASkippedFrameTheFlowRunsFromThatFrame) {
  const Positions points = square_points(0);
  const cv::Rect box = facing_box(unit_square(), points, kCamera, {640, 480}, 8);
  FaceFlow flow;
  EXPECT_TRUE(flow.next(frame(0), box, 0).empty());
  flow.skip(frame(0.45f), box, 1);
  const FlowPair pair = flow.next(frame(0.9f), box, 2);  // 6 px on from the skipped frame, 12 from the first
  ASSERT_FALSE(pair.empty());
  const Vec2f centre = pair.window(Vec2f(320, 240));
  EXPECT_NEAR(pair.back.at<cv::Vec2f>(cvRound(centre.y()), cvRound(centre.x()))[0], -6.0f * pair.window.scale, 0.3f);
  flow.skip(frame(0.9f), box, 4);  // frame 3 missing: starts afresh
  EXPECT_FALSE(flow.next(frame(0.9f), box, 5).empty());
  flow.skip(frame(0.9f), box, 7);
  EXPECT_TRUE(flow.next(frame(0.9f), box, 9).empty());  // frame 8 missing
}

// Told that nothing changed colour on the face, the mover skips its flows
// while it carries nothing, and finds what it would have found: none. It
// does not skip while it carries a cover (the flow carries the evidence),
// and the frame after a skipped one is measured from it.
TEST(MovingCover, WhereNothingChangedColourItFindsWhatTheFlowWouldHave) {
  const MillimetreGrid g = grid();
  MovingCover always(unit_square(), g), gated(unit_square(), g);
  const cv::Mat seen(g.map.size, g.map.size, CV_32F, cv::Scalar(1));
  const Positions still = square_points(0);
  int index = 0;
  auto both = [&](const cv::Mat& image, bool changed) {
    const cv::Mat a = always.update(image, still, kCamera, seen, index);
    const cv::Mat b = gated.update(image, still, kCamera, seen, index, changed);
    ++index;
    return cv::norm(a, b, cv::NORM_INF);
  };
  for (int i = 0; i < 4; ++i) EXPECT_EQ(both(frame(0), false), 0.0) << i;  // nothing moves
  cv::Point cover(180, 250);
  for (int i = 0; i < 8; ++i) {  // in from the left at 12 px a frame: its colours come
    cover.x += 12;
    EXPECT_EQ(both(frame(0, cover), true), 0.0) << i;
  }
  for (int i = 0; i < 6; ++i) EXPECT_EQ(both(frame(0, cover), false), 0.0) << i;  // resting: carried all the same
  cv::Mat e = gated.update(frame(0, cover), still, kCamera, seen, index++, false);
  EXPECT_GT(evidence_at(e, cover, 0), 0.8f);

  // Told wrongly that nothing changed while a cover comes in, it does not
  // look; told on the next frame, it finds the cover from the last frame.
  MovingCover told(unit_square(), g);
  cover = {180, 250};
  EXPECT_EQ(largest(told.update(frame(0), still, kCamera, seen, 0, true)), 0.0);
  for (int i = 1; i < 4; ++i) {
    cover.x += 12;
    EXPECT_EQ(largest(told.update(frame(0, cover), still, kCamera, seen, i, false)), 0.0) << i;
  }
  cover.x += 12;
  e = told.update(frame(0, cover), still, kCamera, seen, 4, true);
  EXPECT_GT(evidence_at(e, cover, 0), 0.99f);
}

// A resting cover fades; once no evidence reaches one half, which counts
// for nothing, it is dropped, and the flow is no longer needed for it.
TEST(MovingCover, EvidenceUnderOneHalfIsDroppedAndNeedsNoFlow) {
  const MillimetreGrid g = grid();
  MovingCoverOptions o;
  o.half_life_frames = 4;
  MovingCover mover(unit_square(), g, o);
  const cv::Mat seen(g.map.size, g.map.size, CV_32F, cv::Scalar(1));
  const Positions still = square_points(0);
  int index = 0;
  mover.update(frame(0), still, kCamera, seen, index++);
  EXPECT_FALSE(mover.measured_motion());  // no last frame
  cv::Point cover(180, 250);
  cv::Mat e;
  for (int i = 0; i < 8; ++i) {
    cover.x += 12;
    e = mover.update(frame(0, cover), still, kCamera, seen, index++);
  }
  ASSERT_GT(evidence_at(e, cover, 0), 0.99f);
  // Resting, nothing changing colour: carried, and measured, while it counts.
  int rested = 0;
  while (largest(e) >= 0.5 && rested < 20) {
    e = mover.update(frame(0, cover), still, kCamera, seen, index++, false);
    EXPECT_TRUE(mover.measured_motion()) << rested;
    ++rested;
  }
  EXPECT_GE(rested, 4);  // one half-life at least
  EXPECT_LE(rested, 6);
  EXPECT_GT(largest(e), 0.0);  // this frame's faded evidence, under one half
  e = mover.update(frame(0, cover), still, kCamera, seen, index++, false);
  EXPECT_FALSE(mover.measured_motion());
  EXPECT_EQ(largest(e), 0.0);
}

// The box around what faces the camera: 171 px across at the image's
// centre, 8 px more each side; none for the square turned away.
TEST(FaceFlow, TheFacingBoxHoldsTheSkinThatFacesTheCamera) {
  const Positions points = square_points(0);
  EXPECT_EQ(facing_box(unit_square(), points, kCamera, {640, 480}, 8),
            cv::Rect(cv::Point(226, 146), cv::Point(415, 335)));
  // Cut to the image.
  EXPECT_EQ(facing_box(unit_square(), points, kCamera, {400, 300}, 8),
            cv::Rect(cv::Point(226, 146), cv::Point(400, 300)));
  TriangleMesh away = unit_square();
  for (Triangle& t : away.triangles) std::swap(t[1], t[2]);
  EXPECT_TRUE(facing_box(away, points, kCamera, {640, 480}, 8).empty());
}

TEST(MovingCover, RejectsImpossibleOptions) {
  MovingCoverOptions o;
  o.half_life_frames = 0;
  EXPECT_THROW(MovingCover(unit_square(), grid(), o), Error);
  o = {};
  o.flow_width = 4;
  EXPECT_THROW(MovingCover(unit_square(), grid(), o), Error);
}

}  // namespace facecap
