// A photo's texture completed from its mirror image; what is not skin dropped.
#include "facecap/swap/face_texture.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace facecap {

namespace {

constexpr int kSize = 128;

// Stripes along v: detail the mirror should carry across.
float stripes(int y) { return std::sin(0.5f * float(y)); }

// The left half seen squarely with skin 0.5 and stripes; the right half seen
// obliquely (weight 0.2) as a flat, darker 0.3; one column pair unseen.
FaceTexture half_seen_face() {
  FaceTexture t;
  t.albedo = cv::Mat(kSize, kSize, CV_32FC3);
  t.weight = cv::Mat(kSize, kSize, CV_32F);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const bool left = x < kSize / 2;
      const float v = left ? 0.5f + 0.1f * stripes(y) : 0.3f;
      t.albedo.at<cv::Vec3f>(y, x) = cv::Vec3f(v, v, v);
      t.weight.at<float>(y, x) = left ? 1.0f : 0.2f;
    }
    t.weight.at<float>(y, 5) = t.weight.at<float>(y, kSize - 1 - 5) = 0.0f;
  }
  return t;
}

}  // namespace

TEST(CompleteFromMirror, TheObliqueSideTakesTheMirrorsDetailInItsOwnColour) {
  const FaceTexture before = half_seen_face();
  FaceTexture t{before.albedo.clone(), before.weight.clone()};
  complete_from_mirror(t, 4.0);
  double mean = 0, cov = 0, var_s = 0, var_t = 0;
  int count = 0;
  for (int y = 0; y < kSize; ++y) {
    // Far from the middle, where the low-pass colour mixes the halves.
    for (int x = kSize / 2 + 16; x < kSize - 16; ++x) {
      const float v = t.albedo.at<cv::Vec3f>(y, x)[1];
      mean += v;
      ++count;
      EXPECT_FLOAT_EQ(t.weight.at<float>(y, x), 1.0f);
    }
  }
  mean /= count;
  // The right side keeps its own (darker) colour...
  EXPECT_NEAR(mean, 0.3, 0.01);
  // ...and gains the left side's stripes, scaled to it (0.8 of 0.1 * 0.3 / 0.5).
  for (int y = 0; y < kSize; ++y) {
    const double v = t.albedo.at<cv::Vec3f>(y, kSize - 20)[1] - mean, s = stripes(y);
    cov += v * s;
    var_s += s * s;
    var_t += v * v;
  }
  EXPECT_GT(cov / std::sqrt(var_s * var_t), 0.95);
  EXPECT_NEAR(cov / var_s, 0.8 * 0.1 * 0.3 / 0.5, 0.01);
  // The squarely seen side is untouched, and what neither side saw stays unseen.
  EXPECT_EQ(cv::norm(t.albedo.colRange(0, kSize / 2), before.albedo.colRange(0, kSize / 2), cv::NORM_INF), 0.0);
  for (int y = 0; y < kSize; ++y) {
    EXPECT_EQ(t.weight.at<float>(y, 5), 0.0f);
    EXPECT_EQ(t.weight.at<float>(y, kSize - 1 - 5), 0.0f);
  }
}

TEST(CompleteFromMirror, AnUnseenTexelAmongSeenOnesTakesTheMirrorInItsNeighboursColour) {
  // A column unseen (a dropped shadow) inside the obliquely seen side: the
  // mirror brings its detail, in the colour of the seen neighbours (0.3),
  // not its own (0.5 + stripes): that would be a pale patch.
  FaceTexture t = half_seen_face();
  for (int y = 0; y < kSize; ++y) t.weight.at<float>(y, kSize - 20) = 0.0f;
  complete_from_mirror(t, 4.0);
  double mean = 0;
  for (int y = 0; y < kSize; ++y) {
    mean += t.albedo.at<cv::Vec3f>(y, kSize - 20)[0] / kSize;
    EXPECT_FLOAT_EQ(t.weight.at<float>(y, kSize - 20), 1.0f);
  }
  EXPECT_NEAR(mean, 0.3, 0.01);
}

TEST(CompleteFromMirror, AnUnseenRegionTakesTheMirrorAsItIs) {
  // Where this side saw nothing in the low-pass neighbourhood, its colour is
  // unknown: the mirror's is copied.
  FaceTexture t = half_seen_face();
  for (int y = 0; y < kSize; ++y)
    for (int x = kSize / 2; x < kSize; ++x) t.weight.at<float>(y, x) = 0.0f;
  complete_from_mirror(t, 4.0);
  for (int y = 0; y < kSize; ++y) {
    EXPECT_FLOAT_EQ(t.albedo.at<cv::Vec3f>(y, kSize - 20)[0], t.albedo.at<cv::Vec3f>(y, 19)[0]);
    EXPECT_FLOAT_EQ(t.weight.at<float>(y, kSize - 20), 1.0f);
  }
}

TEST(ScaleDetail, ScalesTheDetailFinerThanSigmaAndKeepsTheRest) {
  // A constant, a slow ramp along x and a sine along y with a 12-texel
  // period: the blur of sigma 16 removes the sine and keeps the ramp.
  constexpr int kN = 256;
  cv::Mat albedo(kN, kN, CV_32FC3);
  auto sine = [](int y) { return 0.05f * std::sin(2.0f * 3.14159265f * float(y) / 12.0f); };
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const float v = 0.4f + 0.001f * float(x) + sine(y);
      albedo.at<cv::Vec3f>(y, x) = cv::Vec3f(v, v, v);
    }
  const cv::Mat out = scale_detail(albedo, 16.0, 0.7f);
  // Away from the borders, where the blur sees past the edge.
  for (int y = 64; y < kN - 64; ++y)
    for (int x = 64; x < kN - 64; x += 16) {
      const float expected = 0.4f + 0.001f * float(x) + 0.7f * sine(y);
      EXPECT_NEAR(out.at<cv::Vec3f>(y, x)[1], expected, 2e-3f) << "at " << x << ", " << y;
    }
  // A gain of 1 changes nothing.
  EXPECT_LT(cv::norm(scale_detail(albedo, 16.0, 1.0f), albedo, cv::NORM_INF), 1e-5);
}

// A grainy skin texture with a blue collar, dark hair and a white
// highlight, each a square a twelfth of the side; a row unseen. The medians come from
// every third texel each way on this size (65k seen) and from every texel on
// a small one: either way exactly the three blocks are dropped.
TEST(DropNonSkin, DropsWhatIsFarFromTheSkinsMedianColourOrBrightness) {
  for (const int size : {256, 40}) {
    FaceTexture t;
    t.albedo = cv::Mat(size, size, CV_32FC3);
    cv::RNG(7).fill(t.albedo, cv::RNG::UNIFORM, cv::Scalar(0.33, 0.43, 0.58), cv::Scalar(0.37, 0.47, 0.62));
    t.weight = cv::Mat(size, size, CV_32F, cv::Scalar(1));
    const int block = size / 12;
    t.albedo(cv::Rect(0, 0, block, block)).setTo(cv::Scalar(0.6, 0.3, 0.2));                    // blue (BGR)
    t.albedo(cv::Rect(size - block, 0, block, block)).setTo(cv::Scalar(0.05, 0.06, 0.08));      // hair
    t.albedo(cv::Rect(0, size - block, block, block)).setTo(cv::Scalar(0.95, 1.2, 1.6) * 2.0);  // highlight
    t.weight.row(size / 2).setTo(0);
    const int dropped = drop_non_skin(t);
    EXPECT_EQ(dropped, 3 * block * block) << size;
    EXPECT_EQ(cv::countNonZero(t.weight), size * size - size - 3 * block * block) << size;
    EXPECT_EQ(t.weight.at<float>(size / 3, size / 3), 1.0f) << size;
  }
}

}  // namespace facecap
