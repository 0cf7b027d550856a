#pragma once
// The colour of the target's light, frame by frame. The SH lighting of
// eq. 4.9 is one grey irradiance shared by the three channels, so a light
// that turns warmer, or a camera whose white balance drifts, changes the
// target face's colour but not its lighting, and a new face rendered under
// that lighting alone keeps the colour of the first frames. Here the
// target's face, against its own albedo (the appearance frames' mean)
// shaded by this frame's lighting, gives one ratio per channel; their
// chromatic part (mean 1: brightness is the SH lighting's business) tints
// the new face alike.
#include <span>

#include "facecap/core/geometry.hpp"
#include "facecap/swap/lit_vertices.hpp"

namespace facecap {

struct LightColourOptions {
  float max_gain = 1.25f;  // per-channel gains are clamped to [1 / max_gain, max_gain]
};

// `lit`: the target face's vertices this frame shows (lit_vertices());
// `albedo`: 3 x N BGR in [0, 1]. Returns the BGR gains (mean 1), or
// (1, 1, 1) where fewer than 50 vertices are lit.
Vec3f light_colour(std::span<const LitVertex> lit, const Positions& albedo, const LightColourOptions& options = {});

}  // namespace facecap
