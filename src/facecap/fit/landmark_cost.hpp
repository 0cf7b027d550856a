#pragma once
// Ceres cost of one landmark (eq. 4.4 under the projection of eq. 4.2), with
// analytic Jacobians: residual = (Pi(R F X + t) - p) / sigma, where
// X = n + B_id a + B_exp w is the landmark's model vertex.
// Parameter blocks: pose (axis-angle rotation, translation: the first 6
// entries of a frame block, frame_block.hpp), expression weights (w),
// identity (a), focal.
#include <ceres/cost_function.h>

#include <Eigen/Core>

namespace facecap {

// What one landmark residual needs; owned by the caller and updated in place
// between solves (observed point, correspondence vertex rows, sigma).
struct LandmarkTerm {
  Eigen::Vector3d neutral = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic> identity_rows;    // 3 x identity modes
  Eigen::Matrix<double, 3, Eigen::Dynamic> expression_rows;  // 3 x expressions
  Eigen::Vector2d observed = Eigen::Vector2d::Zero();        // pixels
  Eigen::Vector2d principal_point = Eigen::Vector2d::Zero();
  double inv_sigma = 1.0;  // 1 / sigma in pixels
};

class LandmarkCost final : public ceres::CostFunction {
 public:
  // The term's rows may be filled later, but must then have these sizes.
  LandmarkCost(const LandmarkTerm* term, int num_identity, int num_expressions);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  const LandmarkTerm* term_;
};

// The identity's part of the landmark's model point, n + B_id a (n alone
// while the term has no identity rows of a's size). Evaluate and callers
// that hold it fixed form it here alike, so both get the same bits.
Eigen::Vector3d identity_shaped_point(const LandmarkTerm& term, const Eigen::Map<const Eigen::VectorXd>& a);

// The landmark's residual (and, where asked, its Jacobians) given its model
// point x = n + B_id a + B_exp w already formed: what Evaluate does after
// forming x, for callers that hold the identity's part fixed. pose: the
// frame block's first 6 entries. False behind the camera.
bool project_landmark(const LandmarkTerm& term, const Eigen::Vector3d& x, const double* pose, double focal,
                      double* residuals, double* jacobian_pose = nullptr, double* jacobian_expression = nullptr,
                      double* jacobian_identity = nullptr, double* jacobian_focal = nullptr);

// d(R(r) v)/dr for the axis-angle r (Gallego & Yezzi 2015): -R [v]x J(r).
Eigen::Matrix3d rotated_point_jacobian(const Eigen::Vector3d& r, const Eigen::Matrix3d& rotation,
                                       const Eigen::Vector3d& v);

}  // namespace facecap
