#pragma once
// Least-squares rigid (or similarity) alignment of one point set onto another
// (Kabsch / Umeyama).
#include "facecap/core/geometry.hpp"

namespace facecap {

struct RigidTransform {
  Mat3d rotation = Mat3d::Identity();
  Vec3d translation = Vec3d::Zero();
  double scale = 1.0;  // 1 for rigid alignments
};

// The transform T minimising sum ||T(source_i) - target_i||^2; with
// `with_scale`, a similarity transform (Umeyama 1991).
RigidTransform align_rigid(const Positions& source, const Positions& target, bool with_scale = false);

// Mean distance between corresponding points after aligning source onto target.
double aligned_mean_distance(const Positions& source, const Positions& target, bool with_scale = false);

}  // namespace facecap
