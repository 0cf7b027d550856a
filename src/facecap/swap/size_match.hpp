#pragma once
// The source face at the target's size. A single photo fixes the shape of a
// face but not its absolute size: a larger face further from a longer lens
// projects to the same landmarks, so the still fit's size follows its focal
// length prior (address_720p_a's first frame as a photo: focal 1294 px at
// 86 cm, where the video's fit finds 1442 px at 92 cm, and a face 3.7 %
// larger). The target's head, ears and hair stay in the frame, so the new face
// takes the target face's size: the source's identity shape is scaled about
// its centroid by the least-squares factor onto the target's identity shape
// (both neutral), and moved onto the target's centroid, in model space before
// the target's pose. The source's proportions are kept.
#include "facecap/core/geometry.hpp"

namespace facecap {

struct SizeMatch {
  double scale = 1.0;
  Vec3d source_centre = Vec3d::Zero();
  Vec3d target_centre = Vec3d::Zero();

  // target_centre + scale (p - source_centre) for each model-space point.
  Positions apply(const Positions& model_points) const;
};

// The scale s minimising sum_i ||s (a_i - a_bar) - (b_i - b_bar)||^2 over
// corresponding points a (source) and b (target).
SizeMatch match_size(const Positions& source, const Positions& target);

}  // namespace facecap
