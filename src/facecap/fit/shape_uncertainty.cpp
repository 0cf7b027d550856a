#include "facecap/fit/shape_uncertainty.hpp"

#include <algorithm>
#include <cmath>

#include "facecap/model/regions.hpp"

namespace facecap {

ShapeUncertainty::ShapeUncertainty(const FaceModel& model, int identity_modes) {
  const int k = std::min(identity_modes, model.num_identity());
  const int first = regions::kFace.first_vertex, n = regions::kFace.num_vertices();
  const Eigen::MatrixXd basis = model.identity_basis.block(3 * first, 0, 3 * n, k).cast<double>();
  // Centre each coordinate's rows over the region.
  Eigen::MatrixXd centred = basis;
  for (int c = 0; c < 3; ++c) {
    Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(k);
    for (int v = 0; v < n; ++v) mean += basis.row(3 * v + c);
    mean /= n;
    for (int v = 0; v < n; ++v) centred.row(3 * v + c) -= mean;
  }
  gram_.noalias() = centred.transpose() * centred / double(n);
}

double ShapeUncertainty::rms_mm(const Eigen::MatrixXd& covariance) const {
  if (covariance.rows() != gram_.rows() || covariance.cols() != gram_.cols()) return 0.0;
  const double mean_square_cm2 = (gram_.cwiseProduct(covariance)).sum();  // trace(G S), both symmetric
  return 10.0 * std::sqrt(std::max(0.0, mean_square_cm2));
}

double ShapeUncertainty::fixed_size_rms_mm(const Eigen::MatrixXd& covariance, const Eigen::VectorXd& size_ray) const {
  if (covariance.rows() != gram_.rows() || size_ray.size() != gram_.rows() || !(size_ray.norm() > 0)) {
    return rms_mm(covariance);
  }
  const Eigen::VectorXd u = size_ray.normalized();
  const Eigen::MatrixXd off = Eigen::MatrixXd::Identity(u.size(), u.size()) - u * u.transpose();
  return rms_mm(off * covariance * off);
}

}  // namespace facecap
