#include "facecap/fit/identity_size.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "facecap/model/regions.hpp"

namespace facecap {

namespace {

// Least-squares coefficients of the neutral face in the identity basis over
// `vertices`, both centred (a pose's translation absorbs any shift).
Eigen::VectorXd mean_coefficients_over(const FaceModel& model, const std::vector<int>& ids, int k) {
  const int n = static_cast<int>(ids.size());
  const auto rows = [&](int v) { return 3 * ids[v]; };
  Eigen::VectorXd mean_neutral = Eigen::VectorXd::Zero(3);
  Eigen::MatrixXd mean_basis = Eigen::MatrixXd::Zero(3, k);
  for (int v = 0; v < n; ++v) {
    mean_neutral += model.neutral.segment<3>(rows(v)).cast<double>();
    mean_basis += model.identity_basis.block(rows(v), 0, 3, k).cast<double>();
  }
  mean_neutral /= n;
  mean_basis /= n;
  Eigen::MatrixXd btb = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd btx = Eigen::VectorXd::Zero(k);
  for (int v = 0; v < n; ++v) {
    const Eigen::MatrixXd b = model.identity_basis.block(rows(v), 0, 3, k).cast<double>() - mean_basis;
    const Eigen::Vector3d x = model.neutral.segment<3>(rows(v)).cast<double>() - mean_neutral;
    btb.noalias() += b.transpose() * b;
    btx.noalias() += b.transpose() * x;
  }
  return btb.ldlt().solve(btx);
}

}  // namespace

IdentitySizeCorrection::IdentitySizeCorrection(const FaceModel& model, int identity_modes,
                                               const std::vector<int>& fitted_vertices) {
  const int k = std::min(identity_modes, model.num_identity());
  std::vector<int> face(regions::kFace.num_vertices());
  for (size_t v = 0; v < face.size(); ++v) face[v] = regions::kFace.first_vertex + static_cast<int>(v);
  mean_ = mean_coefficients_over(model, face, k);
  fitted_mean_ = fitted_vertices.empty() ? mean_ : mean_coefficients_over(model, fitted_vertices, k);
}

double IdentitySizeCorrection::factor(const Eigen::VectorXd& identity, double determined) const {
  if (identity.size() != mean_.size() || !(determined > 0)) return 1.0;
  const double k = std::min(determined, static_cast<double>(mean_.size() - 1));
  const Eigen::VectorXd b = identity + mean_;
  const double length = b.norm();
  if (!(length > 0)) return 1.0;
  const double along = b.dot(mean_) / length;  // d.m: the prior's peak on the ray
  if (!(along > 0)) return 1.0;
  const double peak_of_mass = 0.5 * (along + std::sqrt(along * along + 4.0 * k));
  return peak_of_mass / along;
}

Eigen::VectorXd IdentitySizeCorrection::scale(const Eigen::VectorXd& identity, double c) const {
  if (c == 1.0) return identity;
  return c * (identity + fitted_mean_) - fitted_mean_;
}

Eigen::VectorXd IdentitySizeCorrection::apply(const Eigen::VectorXd& identity, double determined) const {
  return scale(identity, factor(identity, determined));
}

}  // namespace facecap
