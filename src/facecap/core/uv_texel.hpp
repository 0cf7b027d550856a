#pragma once
// Where a UV (u right, v up, as in OBJ and glTF) falls on a square texture:
// texel (x, y) covers u in [x / N, (x + 1) / N) and its centre is at
// u = (x + 0.5) / N, v = 1 - (y + 0.5) / N (row 0 at the top, v = 1), as
// Blender, three.js, OpenGL and Nuke's STMap read a texture. Everything
// facecap bakes into a texture or reads out of one goes through this,
// so that what it writes is read back at the point it was baked for.
#include "facecap/core/geometry.hpp"

namespace facecap {

// Texel coordinates (texel centres at integers) of a UV on a `size`-texel square.
inline Vec2f uv_to_texel(const Vec2f& uv, int size) {
  const float n = float(size);
  return {uv.x() * n - 0.5f, (1.0f - uv.y()) * n - 0.5f};
}

}  // namespace facecap
