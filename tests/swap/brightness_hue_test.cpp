#include "facecap/swap/brightness_hue.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "facecap/swap/albedo_adaptation.hpp"
#include "swap/square_grid.hpp"

namespace facecap {

TEST(BrightnessHue, RoundTripsAnAlbedo) {
  for (const Vec3f& bgr :
       {Vec3f(0.35f, 0.45f, 0.65f), Vec3f(0.06f, 0.08f, 0.12f), Vec3f(0.5f, 0.5f, 0.5f), Vec3f(0.9f, 0.2f, 0.05f)}) {
    const Vec3f yc = to_brightness_hue(bgr);
    EXPECT_NEAR(yc[0], bgr.mean(), 1e-6f);
    EXPECT_LT((from_brightness_hue(yc) - bgr).cwiseAbs().maxCoeff(), 1e-5f) << bgr.transpose();
  }
  EXPECT_EQ(to_brightness_hue(Vec3f(0.5f, 0.5f, 0.5f)).tail<2>(), Eigen::Vector2f::Zero());
  // No brightness is black; a channel at 0 counts as kDarkestAlbedo for its hue.
  EXPECT_EQ(from_brightness_hue(Vec3f(-0.1f, 0.3f, 0.2f)), Vec3f::Zero());
  EXPECT_TRUE(to_brightness_hue(Vec3f(0, 0.2f, 0.4f)).allFinite());
}

// The swap's adaptation (eq. 6.3) on a face whose one vertex is a dark brown
// brow, from a warm skin to a nearly grey one: offset in brightness and hue,
// the brow keeps its hue and its brightness step to the skin; offset per B,
// G, R channel, as the paper writes it, the brow turns blue.
TEST(BrightnessHue, AdaptingInItKeepsADarkFeaturesHueAndContrast) {
  const int n = 12, count = (n + 1) * (n + 1), brow = 6 * (n + 1) + 6;
  const std::vector<Triangle> grid = test::square_grid(n);
  const Vec3f skin(0.35f, 0.45f, 0.65f), dark(0.06f, 0.08f, 0.12f);  // BGR: warm skin, dark brown brow
  const Vec3f graded(0.50f, 0.52f, 0.56f);                           // the target's skin: nearly grey
  Positions source = skin.replicate(1, count);
  source.col(brow) = dark;
  const Positions target = graded.replicate(1, count);
  const AlbedoAdaptation adapt(grid, count, std::vector<bool>(count, true));

  const Positions offset = adapt.offset(to_brightness_hue(source), to_brightness_hue(target));
  const Vec3f adapted_brow = from_brightness_hue(to_brightness_hue(dark) + Vec3f(offset.col(brow)));
  const Vec3f adapted_skin = from_brightness_hue(to_brightness_hue(skin) + Vec3f(offset.col(0)));
  EXPECT_LT((adapted_skin - graded).cwiseAbs().maxCoeff(), 1e-4f);  // the outline takes the target
  EXPECT_LT(adapted_brow[0], adapted_brow[2]);                      // still browner than blue
  EXPECT_NEAR(adapted_skin.mean() - adapted_brow.mean(), skin.mean() - dark.mean(), 1e-4f);

  const Vec3f per_channel = dark + adapt.offset(source, target).col(brow);
  EXPECT_GT(per_channel[0], per_channel[2]);  // the paper's form: blue over red
}

}  // namespace facecap
