#include "facecap/fit/landmark_cost.hpp"

#include <Eigen/Geometry>

#include "facecap/core/geometry.hpp"
#include "facecap/fit/frame_block.hpp"

namespace facecap {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace

Eigen::Matrix3d rotated_point_jacobian(const Eigen::Vector3d& r, const Eigen::Matrix3d& rotation,
                                       const Eigen::Vector3d& v) {
  const double theta2 = r.squaredNorm();
  if (theta2 < 1e-16) return -skew(v);
  return -rotation * skew(v) * (r * r.transpose() + (rotation.transpose() - Eigen::Matrix3d::Identity()) * skew(r)) /
         theta2;
}

LandmarkCost::LandmarkCost(const LandmarkTerm* term, int num_identity, int num_expressions) : term_(term) {
  set_num_residuals(2);
  mutable_parameter_block_sizes()->push_back(frame_block::kExpression);
  mutable_parameter_block_sizes()->push_back(num_expressions);
  mutable_parameter_block_sizes()->push_back(num_identity);
  mutable_parameter_block_sizes()->push_back(1);
}

bool LandmarkCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const LandmarkTerm& t = *term_;
  const int ne = static_cast<int>(t.expression_rows.cols());
  const int ni = static_cast<int>(t.identity_rows.cols());
  const double* pose = parameters[0];
  const Eigen::Map<const Eigen::Vector3d> r(pose + frame_block::kRotation);
  const Eigen::Map<const Eigen::Vector3d> translation(pose + frame_block::kTranslation);
  const Eigen::Map<const Eigen::VectorXd> w(parameters[1], ne);
  const Eigen::Map<const Eigen::VectorXd> a(parameters[2], ni);
  const double focal = parameters[3][0];

  Eigen::Vector3d x = t.neutral;
  if (ni > 0) x.noalias() += t.identity_rows * a;
  x.noalias() += t.expression_rows * w;
  const Eigen::Vector3d v(x.x(), -x.y(), -x.z());  // F: model into camera convention
  const Eigen::Matrix3d rotation = rotation_from_axis_angle(r);
  const Eigen::Vector3d y = rotation * v + translation;
  if (y.z() <= 1e-6) return false;  // behind the camera: reject the step
  const double inv_z = 1.0 / y.z();
  const double u = y.x() * inv_z, q = y.y() * inv_z;
  residuals[0] = t.inv_sigma * (focal * u + t.principal_point.x() - t.observed.x());
  residuals[1] = t.inv_sigma * (focal * q + t.principal_point.y() - t.observed.y());
  if (jacobians == nullptr) return true;

  // d residual / d y (2 x 3)
  Eigen::Matrix<double, 2, 3> dr_dy;
  const double s = t.inv_sigma * focal * inv_z;
  dr_dy << s, 0, -s * u, 0, s, -s * q;
  // d y / d X = R F
  Eigen::Matrix3d rf = rotation;
  rf.col(1) *= -1.0;
  rf.col(2) *= -1.0;
  const Eigen::Matrix<double, 2, 3> dr_dx = dr_dy * rf;

  using RowMajor2 = Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> j(jacobians[0]);
    j.block<2, 3>(0, frame_block::kRotation) = dr_dy * rotated_point_jacobian(r, rotation, v);
    j.block<2, 3>(0, frame_block::kTranslation) = dr_dy;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<RowMajor2> j(jacobians[1], 2, ne);
    j.noalias() = dr_dx * t.expression_rows;
  }
  if (jacobians[2] != nullptr && ni > 0) {
    Eigen::Map<RowMajor2> j(jacobians[2], 2, ni);
    j.noalias() = dr_dx * t.identity_rows;
  }
  if (jacobians[3] != nullptr) {
    jacobians[3][0] = t.inv_sigma * u;
    jacobians[3][1] = t.inv_sigma * q;
  }
  return true;
}

}  // namespace facecap
