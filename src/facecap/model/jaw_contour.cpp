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

std::array<int, 17> silhouette_vertices(const JawContour& contour, const Positions& face_positions,
                                        const Mat3d& model_to_camera, const Vec3d& translation, double focal) {
  std::array<int, 17> out{};
  const Mat3f r = model_to_camera.cast<float>();
  const Vec3f t = translation.cast<float>();
  for (int k = 0; k < 17; ++k) {
    const auto& line = contour.lines[k];
    const float outward = k < 8 ? -1.0f : 1.0f;  // subject's right side appears at image left
    float best = -std::numeric_limits<float>::infinity();
    int best_v = line.front();
    for (int v : line) {
      const Vec3f p = r * face_positions.col(v) + t;
      const float x = float(focal) * p.x() / p.z();
      if (outward * x > best) {
        best = outward * x;
        best_v = v;
      }
    }
    out[k] = best_v;
  }
  return out;
}

std::array<int, 68> landmark_vertices_for_pose(const FaceModel& model, const JawContour& contour,
                                               const Positions& face_positions, const Mat3d& model_to_camera,
                                               const Vec3d& translation, double focal) {
  std::array<int, 68> out{};
  std::copy(model.landmarks.vertices.begin(), model.landmarks.vertices.end(), out.begin());
  const auto jaw = silhouette_vertices(contour, face_positions, model_to_camera, translation, focal);
  std::copy(jaw.begin(), jaw.end(), out.begin());
  return out;
}

}  // namespace facecap
