#include "facecap/model/jaw_contour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facecap {

JawContour build_jaw_contour(const FaceModel& model) {
  const Region& face = regions::kFace;
  Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
  JawContour contour;
  const LandmarkMap& lm = model.landmarks;
  for (int k = 0; k < 17; ++k) {
    if (k == 8) {
      contour.lines[k] = {lm.vertices[8]};
      continue;
    }
    const int candidate = k < 8 ? lm.jaw_right[k] : lm.jaw_left[k - 9];
    const Vec3f c = neutral.col(candidate);
    const float side = c.x() < 0 ? -1.0f : 1.0f;
    // Where the line ends toward the middle: the landmark map's own vertex for
    // this landmark lies on the front of the cheek; go a little beyond it.
    const Vec3f front = neutral.col(lm.vertices[k]);
    const float inner_x = std::abs(front.x()) * 0.55f;
    std::vector<std::pair<float, int>> line;
    for (int v = face.first_vertex; v <= face.last_vertex; ++v) {
      const Vec3f p = neutral.col(v);
      if (p.x() * side <= 0) continue;
      if (std::abs(p.y() - c.y()) > 0.22f) continue;
      if (std::abs(p.x()) > std::abs(c.x()) + 0.05f || std::abs(p.x()) < inner_x) continue;
      if (p.z() < c.z() - 0.05f) continue;  // stay on the front surface
      line.emplace_back(-std::abs(p.x()), v);
    }
    std::sort(line.begin(), line.end());
    contour.lines[k].push_back(candidate);
    for (const auto& [key, v] : line) {
      if (v != candidate) contour.lines[k].push_back(v);
    }
  }
  return contour;
}

std::array<int, 17> silhouette_vertices(const JawContour& contour,
                                        const std::function<Vec3d(int vertex)>& camera_position) {
  std::array<int, 17> out{};
  for (int k = 0; k < 17; ++k) {
    const auto& line = contour.lines[k];
    const double outward = k < 8 ? -1.0 : 1.0;  // subject's right side appears at image left
    double best = -std::numeric_limits<double>::infinity();
    int best_v = line.front();
    for (int v : line) {
      const Vec3d p = camera_position(v);
      // x/z orders points by image column for any focal length.
      const double x = outward * p.x() / p.z();
      if (x > best) {
        best = x;
        best_v = v;
      }
    }
    out[k] = best_v;
  }
  return out;
}

std::array<int, 17> silhouette_vertices(const JawContour& contour, const Positions& face_positions,
                                        const Mat3d& model_to_camera, const Vec3d& translation) {
  return silhouette_vertices(contour, [&](int v) -> Vec3d {
    return model_to_camera * face_positions.col(v).cast<double>() + translation;
  });
}

std::array<int, 68> landmark_vertices_for_pose(const FaceModel& model, const JawContour& contour,
                                               const Positions& face_positions, const Mat3d& model_to_camera,
                                               const Vec3d& translation) {
  std::array<int, 68> out{};
  std::copy(model.landmarks.vertices.begin(), model.landmarks.vertices.end(), out.begin());
  const auto jaw = silhouette_vertices(contour, face_positions, model_to_camera, translation);
  std::copy(jaw.begin(), jaw.end(), out.begin());
  return out;
}

}  // namespace facecap
