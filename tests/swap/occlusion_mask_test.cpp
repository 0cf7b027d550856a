// What covers the target face: colours the appearance frames never showed
// nearby, filled and feathered; sliding features and light changes are not covers.
#include "facecap/swap/occlusion_mask.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "swap/unit_square.hpp"

namespace facecap {

namespace {

// At 128 mm per UV unit and 1 mm per texel the grid of test::unit_square()
// is 128 texels square.
using test::largest;
using test::unit_square;

constexpr double kMmPerUv = 128.0;
const cv::Vec3f kSkin(0.35f, 0.45f, 0.6f);  // BGR
const cv::Vec3f kNavy(0.38f, 0.19f, 0.13f);
const cv::Vec3f kBrow(0.08f, 0.09f, 0.1f);

// Skin seen everywhere, with a dark band (a brow) across rows [brow, brow + 8).
FaceTexture skin(int size, int brow = -100) {
  FaceTexture t;
  t.albedo = cv::Mat(size, size, CV_32FC3, cv::Scalar(kSkin[0], kSkin[1], kSkin[2]));
  t.weight = cv::Mat(size, size, CV_32F, cv::Scalar(1));
  if (brow >= 0) t.albedo.rowRange(brow, brow + 8).setTo(cv::Scalar(kBrow[0], kBrow[1], kBrow[2]));
  return t;
}

FaceTexture with_disc(FaceTexture t, cv::Point centre, int radius, cv::Vec3f colour) {
  t.albedo = t.albedo.clone();
  cv::circle(t.albedo, centre, radius, cv::Scalar(colour[0], colour[1], colour[2]), cv::FILLED);
  return t;
}

}  // namespace

TEST(OcclusionMask, NothingIsCoveredWithoutAReferenceOrAChange) {
  OcclusionMask mask(unit_square(), kMmPerUv);
  const int n = mask.grid_size();
  ASSERT_EQ(n, 128);
  const FaceTexture face = skin(n, 40);
  EXPECT_EQ(largest(mask.covered(face)), 0.0);  // no reference yet
  mask.add_reference(face);
  EXPECT_EQ(largest(mask.covered(face)), 0.0);
}

TEST(OcclusionMask, ACoverOfAnotherColourIsCoveredAndFeatheredAtItsEdge) {
  OcclusionMask mask(unit_square(), kMmPerUv);
  const int n = mask.grid_size();
  mask.add_reference(skin(n, 20));
  const cv::Mat c = mask.covered(with_disc(skin(n, 20), {64, 80}, 15, kNavy));
  EXPECT_GT(c.at<float>(80, 64), 0.99f);
  EXPECT_GT(c.at<float>(80, 64 + 14), 0.99f);  // its edge, inside the 2 mm margin
  EXPECT_GT(c.at<float>(80, 64 + 16), 0.5f);
  EXPECT_GT(c.at<float>(80, 64 + 18), 0.0f);  // fading past the margin
  EXPECT_LT(c.at<float>(80, 64 + 18), 0.5f);
  EXPECT_EQ(c.at<float>(80, 64 + 24), 0.0f);
  EXPECT_EQ(c.at<float>(20, 20), 0.0f);
  // So is a white one (a microphone) over the brow. (A dark one there is
  // found only away from the brow's edges, where the appearance frames saw
  // both the brow's colour and the skin's.)
  const cv::Vec3f white(0.95f, 0.95f, 0.95f);
  EXPECT_GT(mask.covered(with_disc(skin(n, 20), {64, 24}, 15, white)).at<float>(24, 64), 0.99f);
}

TEST(OcclusionMask, SlidingFeaturesSpecksAndLightAreNoCover) {
  OcclusionMask mask(unit_square(), kMmPerUv);
  const int n = mask.grid_size();
  mask.add_reference(skin(n, 40));
  // The brow 4 mm lower (the tracking slid it), within slide_mm; 10 mm
  // lower, the 6 mm past slide_mm are narrower than a cover.
  EXPECT_EQ(largest(mask.covered(skin(n, 44))), 0.0);
  EXPECT_EQ(largest(mask.covered(skin(n, 50))), 0.0);
  // 12 mm lower is a change no slide explains: the brow's new rows are covered.
  EXPECT_GT(largest(mask.covered(skin(n, 52))), 0.5);
  // A speck narrower than min_extent_mm.
  FaceTexture speck = skin(n, 40);
  speck.albedo(cv::Rect(64, 90, 2, 2)).setTo(cv::Scalar(kNavy[0], kNavy[1], kNavy[2]));
  EXPECT_EQ(largest(mask.covered(speck)), 0.0);
  // Brighter light, of another colour: the frame's overall shift.
  FaceTexture warm = skin(n, 40);
  cv::multiply(warm.albedo, cv::Scalar(1.4, 1.8, 2.2), warm.albedo);
  EXPECT_EQ(largest(mask.covered(warm)), 0.0);
}

TEST(OcclusionMask, CoversFillWhatTheyEncloseAndReachIntoWhatIsNotSeen) {
  OcclusionMask mask(unit_square(), kMmPerUv);
  const int n = mask.grid_size();
  mask.add_reference(skin(n));
  // A ring of cover 20 texels across inside: its middle is covered too.
  FaceTexture ring = with_disc(skin(n), {64, 64}, 30, kNavy);
  cv::circle(ring.albedo, {64, 64}, 20, cv::Scalar(kSkin[0], kSkin[1], kSkin[2]), cv::FILLED);
  EXPECT_GT(mask.covered(ring).at<float>(64, 64), 0.99f);
  // Unseen texels next to a cover (the new face's outline may show there),
  // up to unseen_mm; unseen texels far from any cover are not.
  FaceTexture edge = with_disc(skin(n), {64, 105}, 10, kNavy);
  edge.weight.rowRange(112, n).setTo(0);
  edge.weight.colRange(0, 8).setTo(0);
  const cv::Mat c = mask.covered(edge);
  EXPECT_GT(c.at<float>(119, 64), 0.99f);
  EXPECT_LT(c.at<float>(127, 64), 0.5f);  // past unseen_mm (and the margin)
  EXPECT_EQ(c.at<float>(64, 2), 0.0f);
}

TEST(OcclusionMask, RejectsImpossibleOptions) {
  OcclusionOptions o;
  o.min_log_change = 0;
  EXPECT_THROW(OcclusionMask(unit_square(), kMmPerUv, o), Error);
  EXPECT_THROW(OcclusionMask(unit_square(), 0.0), Error);
}

}  // namespace facecap
