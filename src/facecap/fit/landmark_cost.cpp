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
  const Eigen::Map<const Eigen::VectorXd> w(parameters[1], ne);
  const Eigen::Map<const Eigen::VectorXd> a(parameters[2], ni);
  Eigen::Vector3d x = identity_shaped_point(t, a);
  x.noalias() += t.expression_rows * w;
  if (jacobians == nullptr) return project_landmark(t, x, parameters[0], parameters[3][0], residuals);
  return project_landmark(t, x, parameters[0], parameters[3][0], residuals, jacobians[0], jacobians[1], jacobians[2],
                          jacobians[3]);
}

Eigen::Vector3d identity_shaped_point(const LandmarkTerm& t, const Eigen::Map<const Eigen::VectorXd>& a) {
  Eigen::Vector3d x = t.neutral;
  if (t.identity_rows.cols() > 0 && t.identity_rows.cols() == a.size()) x.noalias() += t.identity_rows * a;
  return x;
}

bool project_landmark(const LandmarkTerm& t, const Eigen::Vector3d& x, const double* pose, double focal,
                      double* residuals, double* jacobian_pose, double* jacobian_expression, double* jacobian_identity,
                      double* jacobian_focal) {
  const int ne = static_cast<int>(t.expression_rows.cols());
  const int ni = static_cast<int>(t.identity_rows.cols());
  const Eigen::Map<const Eigen::Vector3d> r(pose + frame_block::kRotation);
  const Eigen::Map<const Eigen::Vector3d> translation(pose + frame_block::kTranslation);
  const Eigen::Vector3d v(x.x(), -x.y(), -x.z());  // F: model into camera convention
  const Eigen::Matrix3d rotation = rotation_from_axis_angle(r);
  const Eigen::Vector3d y = rotation * v + translation;
  if (y.z() <= 1e-6) return false;  // behind the camera: reject the step
  const double inv_z = 1.0 / y.z();
  const double u = y.x() * inv_z, q = y.y() * inv_z;
  residuals[0] = t.inv_sigma * (focal * u + t.principal_point.x() - t.observed.x());
  residuals[1] = t.inv_sigma * (focal * q + t.principal_point.y() - t.observed.y());
  if (jacobian_pose == nullptr && jacobian_expression == nullptr && jacobian_identity == nullptr &&
      jacobian_focal == nullptr)
    return true;

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
  if (jacobian_pose != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> j(jacobian_pose);
    j.block<2, 3>(0, frame_block::kRotation) = dr_dy * rotated_point_jacobian(r, rotation, v);
    j.block<2, 3>(0, frame_block::kTranslation) = dr_dy;
  }
  if (jacobian_expression != nullptr) {
    Eigen::Map<RowMajor2> j(jacobian_expression, 2, ne);
    j.noalias() = dr_dx * t.expression_rows;
  }
  if (jacobian_identity != nullptr && ni > 0) {
    Eigen::Map<RowMajor2> j(jacobian_identity, 2, ni);
    j.noalias() = dr_dx * t.identity_rows;
  }
  if (jacobian_focal != nullptr) {
    jacobian_focal[0] = t.inv_sigma * u;
    jacobian_focal[1] = t.inv_sigma * q;
  }
  return true;
}

}  // namespace facecap
