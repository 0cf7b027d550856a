#pragma once
// The synthetic ground truth's fine detail: a displacement (cm, along the
// surface normal, positive outward) as a function of a surface point's
// position on the neutral mean face (model space, cm). Forehead furrows,
// nasolabial folds, crow's feet and frown lines, 0.3 to 0.9 mm deep.
#include "facecap/core/geometry.hpp"

namespace facecap {

float wrinkle_displacement(const Vec3f& neutral_position);

}  // namespace facecap
