#pragma once
// The target's colour grade in the swap: a desaturated or sepia video shows
// its skin within a narrower range of hues than a photo does, and the albedo
// adaptation (eq. 6.3, an offset harmonic inside the face) cannot narrow a
// range: a photo's ruddy cheeks and lips stay as far from its outline's hue
// as they were. ChromaSpread narrows it: on the hue axes of an albedo's
// brightness and hue (brightness_hue.hpp), each is scaled about the source
// face's median by the ratio of the target face's spread to the source's
// (their 10th-90th percentile ranges over the vertices both show), at most 1:
// a photo's hues are never made stronger than the photo shows them.
// Brightness is left to the adaptation. A departure from the paper.
#include <vector>

#include "facecap/core/geometry.hpp"

namespace facecap {

class ChromaSpread {
 public:
  // No change.
  ChromaSpread() = default;
  // From the source and target vertex albedos in brightness and hue (3 x N)
  // over the vertices `use` marks; no change where fewer than 50 are marked.
  ChromaSpread(const Positions& source, const Positions& target, const std::vector<bool>& use);

  // A brightness and hue with its hue narrowed.
  Vec3f narrow(const Vec3f& yc) const;
  Positions narrow(const Positions& yc) const;

  // The scale on each hue axis (c1, c2), in [0, 1].
  const Eigen::Vector2f& scale() const { return scale_; }

 private:
  Eigen::Vector2f centre_ = Eigen::Vector2f::Zero();
  Eigen::Vector2f scale_ = Eigen::Vector2f::Ones();
};

}  // namespace facecap
