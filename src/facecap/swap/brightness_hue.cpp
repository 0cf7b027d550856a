#include "facecap/swap/brightness_hue.hpp"

namespace facecap {

Vec3f to_brightness_hue(const Vec3f& bgr) {
  const Vec3f l = bgr.cwiseMax(kDarkestAlbedo).array().log();
  return {bgr.mean(), l[0] - l[2], 2.0f * l[1] - l[2] - l[0]};
}

Positions to_brightness_hue(const Positions& bgr) {
  Positions out(3, bgr.cols());
  for (int v = 0; v < static_cast<int>(bgr.cols()); ++v) out.col(v) = to_brightness_hue(Vec3f(bgr.col(v)));
  return out;
}

Vec3f from_brightness_hue(const Vec3f& yc) {
  if (!(yc[0] > 0.0f)) return Vec3f::Zero();
  const float c1 = yc[1], c2 = yc[2];
  // Each channel relative to the geometric mean of the three, then scaled to the brightness.
  const Vec3f ratio = Vec3f(c1 / 2 - c2 / 6, c2 / 3, -c1 / 2 - c2 / 6).array().exp();
  return ratio * (yc[0] / ratio.mean());
}

}  // namespace facecap
