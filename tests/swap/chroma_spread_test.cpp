#include "facecap/swap/chroma_spread.hpp"

#include "facecap/swap/brightness_hue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace facecap {

namespace {

// Albedos (BGR) about `skin` whose log-opponent chroma (log B - log R,
// 2 log G - log R - log B) spreads uniformly over +-`spread`, with their
// brightness (the mean of the logs) varying on its own.
Positions skin_albedos(const Vec3f& skin, float spread, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Positions a(3, count);
  for (int v = 0; v < count; ++v) {
    const float y = 0.2f * u(rng), c1 = spread * u(rng), c2 = spread * u(rng);
    const Vec3f log_offset(y + c1 / 2 - c2 / 6, y + c2 / 3, y - c1 / 2 - c2 / 6);
    a.col(v) = skin.cwiseProduct(Vec3f(log_offset.array().exp()));
  }
  return a;
}

// The 10th-90th percentile range of log B - log R.
float blue_red_spread(const Positions& a) {
  std::vector<float> c;
  for (int v = 0; v < static_cast<int>(a.cols()); ++v) c.push_back(std::log(a(0, v)) - std::log(a(2, v)));
  std::sort(c.begin(), c.end());
  return c[c.size() * 9 / 10] - c[c.size() / 10];
}

const Vec3f kWarmSkin(0.35f, 0.45f, 0.65f), kGradedSkin(0.48f, 0.52f, 0.60f);  // BGR

}  // namespace

TEST(ChromaSpread, ANarrowerTargetNarrowsTheSourcesHuesAndKeepsTheirBrightness) {
  const int count = 2000;
  const Positions source = skin_albedos(kWarmSkin, 0.30f, count, 1);
  const Positions target = skin_albedos(kGradedSkin, 0.12f, count, 2);
  const ChromaSpread grade(to_brightness_hue(source), to_brightness_hue(target), std::vector<bool>(count, true));
  EXPECT_NEAR(grade.scale()[0], 0.4f, 0.03f);
  EXPECT_NEAR(grade.scale()[1], 0.4f, 0.03f);
  Positions narrowed(3, count);
  for (int v = 0; v < count; ++v)
    narrowed.col(v) = from_brightness_hue(grade.narrow(to_brightness_hue(Vec3f(source.col(v)))));
  EXPECT_NEAR(blue_red_spread(narrowed), blue_red_spread(target), 0.1f * blue_red_spread(target));
  for (int v = 0; v < count; v += 97) {
    EXPECT_NEAR(narrowed.col(v).mean(), source.col(v).mean(), 1e-5f) << v;
  }
  // The source's median hue is the centre: a vertex there stays as it is.
  EXPECT_LT((from_brightness_hue(grade.narrow(to_brightness_hue(kWarmSkin))) - kWarmSkin).cwiseAbs().maxCoeff(), 0.01f);
}

TEST(ChromaSpread, AWiderTargetLeavesTheSourceAsItIs) {
  const int count = 2000;
  const Positions source = skin_albedos(kWarmSkin, 0.12f, count, 3);
  const Positions target = skin_albedos(kGradedSkin, 0.30f, count, 4);
  const Positions source_yc = to_brightness_hue(source);
  const ChromaSpread grade(source_yc, to_brightness_hue(target), std::vector<bool>(count, true));
  EXPECT_EQ(grade.scale(), Eigen::Vector2f::Ones());
  EXPECT_EQ(grade.narrow(source_yc), source_yc);
}

TEST(ChromaSpread, OnlyTheMarkedVerticesCountAndTooFewChangeNothing) {
  const int count = 2000;
  const Positions source = skin_albedos(kWarmSkin, 0.30f, count, 5);
  Positions target = skin_albedos(kGradedSkin, 0.12f, count, 6);
  std::vector<bool> use(count, false);
  for (int v = 0; v < count / 2; ++v) use[v] = true;
  // Wild colours where the target was never seen do not widen its spread.
  for (int v = count / 2; v < count; ++v) target.col(v) = Vec3f(0.9f, 0.1f, 0.1f);
  const Positions source_yc = to_brightness_hue(source), target_yc = to_brightness_hue(target);
  EXPECT_NEAR(ChromaSpread(source_yc, target_yc, use).scale()[0], 0.4f, 0.04f);
  std::vector<bool> few(count, false);
  for (int v = 0; v < 49; ++v) few[v] = true;
  EXPECT_EQ(ChromaSpread(source_yc, target_yc, few).scale(), Eigen::Vector2f::Ones());
}

}  // namespace facecap
