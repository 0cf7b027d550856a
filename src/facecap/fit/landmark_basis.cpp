#include "facecap/fit/landmark_basis.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace facecap {

LandmarkBasis gather_landmark_basis(const FaceModel& model, int identity_modes) {
  LandmarkBasis b;
  b.contour = build_jaw_contour(model);
  b.slot_of_vertex.assign(model.num_vertices, -1);
  auto add = [&](int v) {
    if (b.slot_of_vertex.at(v) >= 0) return;
    b.slot_of_vertex[v] = static_cast<int>(b.vertices.size());
    b.vertices.push_back(v);
  };
  for (int v : model.landmarks.vertices) add(v);
  for (const auto& line : b.contour.lines)
    for (int v : line) add(v);
  for (const auto* path : {&b.contour.right_path, &b.contour.left_path})
    for (const auto& line : *path)
      for (int v : line) add(v);
  const int n = static_cast<int>(b.vertices.size());
  const int k = std::min(identity_modes, model.num_identity());
  b.neutral.resize(3, n);
  b.identity.resize(3 * n, k);
  b.expression.resize(3 * n, model.num_expressions());
  for (int s = 0; s < n; ++s) {
    const int row = 3 * b.vertices[s];
    b.neutral.col(s) = model.neutral.segment<3>(row).cast<double>();
    b.identity.middleRows(3 * s, 3) = model.identity_basis.block(row, 0, 3, k).cast<double>();
    b.expression.middleRows(3 * s, 3) = model.expression_basis.middleRows(row, 3).cast<double>();
  }
  const int ne = static_cast<int>(b.expression.cols());
  b.identity_by_slot.resize(3, std::size_t(n) * k);
  b.expression_by_slot.resize(3, std::size_t(n) * ne);
  for (int s = 0; s < n; ++s) {
    b.identity_by_slot.middleCols(std::size_t(s) * k, k) = b.identity.middleRows(3 * s, 3);
    b.expression_by_slot.middleCols(std::size_t(s) * ne, ne) = b.expression.middleRows(3 * s, 3);
  }
  return b;
}

int LandmarkBasis::slot(int vertex) const {
  const int s = vertex >= 0 && std::size_t(vertex) < slot_of_vertex.size() ? slot_of_vertex[vertex] : -1;
  if (s < 0) throw std::out_of_range("vertex " + std::to_string(vertex) + " is not in the landmark basis");
  return s;
}

Eigen::Vector3d LandmarkBasis::position(int s, const Eigen::VectorXd& id, const Eigen::VectorXd& w) const {
  Eigen::Vector3d x = neutral.col(s);
  const Eigen::Index ni = identity.cols(), ne = expression.cols();
  if (id.size() > 0) x.noalias() += identity_by_slot.middleCols(s * ni, id.size()) * id;
  if (w.size() > 0) x.noalias() += expression_by_slot.middleCols(s * ne, ne) * w;
  return x;
}

Correspondences pose_correspondences(const FaceModel& model, const LandmarkBasis& basis,
                                     const Eigen::VectorXd& identity, const Eigen::VectorXd& expression,
                                     const HeadPose& pose, const PinholeCamera& camera, const Landmarks& observed,
                                     bool slide) {
  Correspondences out{};
  for (int i = 0; i < 68; ++i) out[i] = {model.landmarks.vertices[i], model.landmarks.vertices[i], 0.0};
  const Mat3d rf = pose.model_to_camera_rotation();
  const CameraPositionFn camera_position = [&](int v) -> Vec3d {
    return rf * basis.position(basis.slot(v), identity, expression) + pose.translation;
  };
  if (!slide) {
    const auto jaw = silhouette_vertices(basis.contour, camera_position, image_lateral(rf));
    for (int k = 0; k < 17; ++k) out[k] = {jaw[k], jaw[k], 0.0};
    return out;
  }
  for (const bool right : {true, false}) {
    const std::vector<int> path = silhouette_path(basis.contour, right, camera_position, image_lateral(rf));
    std::vector<Vec2d> projected(path.size());
    for (size_t j = 0; j < path.size(); ++j) projected[j] = camera.project(camera_position(path[j]));
    const int last_segment = static_cast<int>(path.size()) - 2;
    for (int k = 0; k < 8; ++k) {
      const int landmark = right ? k : 9 + k;
      // Short-list candidate k sits at extended index 2k + 1 (ear to chin on
      // the right); the left path runs the other way.
      const int nominal = right ? 2 * k + 1 : 15 - 2 * k;
      const Vec2d q = observed[landmark].cast<double>();
      double best = std::numeric_limits<double>::infinity();
      for (int j = std::max(0, nominal - 4); j <= std::min(last_segment, nominal + 3); ++j) {
        const Vec2d d = projected[j + 1] - projected[j];
        const double len2 = d.squaredNorm();
        const double t = len2 > 1e-12 ? std::clamp((q - projected[j]).dot(d) / len2, 0.0, 1.0) : 0.0;
        const double dist = (projected[j] + t * d - q).squaredNorm();
        if (dist < best) {
          best = dist;
          out[landmark] = {path[j], path[j + 1], t};
        }
      }
    }
  }
  return out;
}

}  // namespace facecap
