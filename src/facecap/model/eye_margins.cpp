#include "facecap/model/eye_margins.hpp"

#include <algorithm>
#include <limits>

#include "facecap/model/regions.hpp"

namespace facecap {

std::array<std::vector<int>, 2> eye_margin_loops(const FaceModel& model, const std::vector<Triangle>& skin) {
  const Eigen::VectorXf none;
  const Positions mean = model.with_expression(model.identity_shape(none, regions::kFace), none, regions::kFace);
  std::vector<std::vector<int>> loops = boundary_loops(skin);
  if (!loops.empty()) loops.erase(loops.begin());  // the longest: the outline
  auto centroid = [&](const std::vector<int>& vertices) {
    Vec3f c = Vec3f::Zero();
    for (const int v : vertices) c += mean.col(v);
    return Vec3f(c / float(std::max<size_t>(1, vertices.size())));
  };
  std::array<Vec3f, 2> eye;
  for (int e = 0; e < 2; ++e) {
    const auto first = model.landmarks.vertices.begin() + 36 + 6 * e;
    eye[e] = centroid(std::vector<int>(first, first + 6));
  }
  std::array<std::vector<int>, 2> out;
  for (int e = 0; e < 2; ++e) {
    float best = std::numeric_limits<float>::max();
    for (const std::vector<int>& loop : loops) {
      const Vec3f c = centroid(loop);
      const float d = (c - eye[e]).norm();
      // A loop nearer the other eye is that eye's.
      if (d < best && d < (c - eye[1 - e]).norm()) best = d, out[e] = loop;
    }
  }
  return out;
}

}  // namespace facecap
