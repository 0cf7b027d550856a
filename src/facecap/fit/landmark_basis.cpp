#include "facecap/fit/landmark_basis.hpp"


namespace facecap {

LandmarkBasis gather_landmark_basis(const FaceModel& model, int identity_modes) {
  LandmarkBasis b;
  b.contour = build_jaw_contour(model);
  auto add = [&](int v) {
    if (b.slot_of.count(v)) return;
    b.slot_of.emplace(v, static_cast<int>(b.vertices.size()));
    b.vertices.push_back(v);
  };
  for (int v : model.landmarks.vertices) add(v);
  for (const auto& line : b.contour.lines)
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
  return b;
}

Eigen::Vector3d LandmarkBasis::position(int s, const Eigen::VectorXd& id, const Eigen::VectorXd& w) const {
  Eigen::Vector3d x = neutral.col(s);
  if (id.size() > 0) x.noalias() += identity.middleRows(3 * s, 3).leftCols(id.size()) * id;
  if (w.size() > 0) x.noalias() += expression.middleRows(3 * s, 3) * w;
  return x;
}

std::array<int, 68> pose_correspondences(const FaceModel& model, const LandmarkBasis& basis,
                                         const Eigen::VectorXd& identity, const Eigen::VectorXd& expression,
                                         const Mat3d& model_to_camera, const Vec3d& translation) {
  std::array<int, 68> out{};
  std::copy(model.landmarks.vertices.begin(), model.landmarks.vertices.end(), out.begin());
  const auto jaw = silhouette_vertices(basis.contour, [&](int v) -> Vec3d {
    return model_to_camera * basis.position(basis.slot(v), identity, expression) + translation;
  });
  std::copy(jaw.begin(), jaw.end(), out.begin());
  return out;
}

}  // namespace facecap
