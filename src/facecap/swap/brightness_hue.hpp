#pragma once
// An albedo (linear BGR) as its brightness and its hue: y = (B + G + R) / 3,
// linear, and the log-opponent hue c1 = log B - log R, c2 = 2 log G - log R -
// log B (channels below kDarkestAlbedo count as it). The swap adapts the
// photo's albedo to the target's (eq. 6.3) in these coordinates: brightness
// by an added offset, as the paper does, so that the photo's texture keeps
// its contrast; hue by an offset of logarithms, so that a dark feature keeps
// its own hue rather than take the whole skin's change of colour (the
// paper's per-channel offset turned a photo's dark brows blue on a
// desaturated video). A departure from the paper, measured in the README.
#include "facecap/core/geometry.hpp"

namespace facecap {

inline constexpr float kDarkestAlbedo = 0.02f;

// (y, c1, c2) of a BGR albedo.
Vec3f to_brightness_hue(const Vec3f& bgr);
Positions to_brightness_hue(const Positions& bgr);
// The BGR albedo of (y, c1, c2); black where y <= 0.
Vec3f from_brightness_hue(const Vec3f& yc);

}  // namespace facecap
