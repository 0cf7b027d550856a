#include "facecap/core/rigid_alignment.hpp"

#include <Eigen/SVD>

namespace facecap {

RigidTransform align_rigid(const Positions& source, const Positions& target, bool with_scale) {
  const Eigen::Matrix3Xd s = source.cast<double>(), t = target.cast<double>();
  const Vec3d ms = s.rowwise().mean(), mt = t.rowwise().mean();
  const Eigen::Matrix3d cov = (t.colwise() - mt) * (s.colwise() - ms).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) d(2, 2) = -1;  // no reflections
  RigidTransform out;
  out.rotation = svd.matrixU() * d * svd.matrixV().transpose();
  if (with_scale) {
    const double var = (s.colwise() - ms).squaredNorm();
    out.scale = var > 0 ? (svd.singularValues().asDiagonal() * d).trace() / var : 1.0;
  }
  out.translation = mt - out.scale * out.rotation * ms;
  return out;
}

double aligned_mean_distance(const Positions& source, const Positions& target, bool with_scale) {
  const RigidTransform tr = align_rigid(source, target, with_scale);
  const Eigen::Matrix3Xd moved = (tr.scale * tr.rotation * source.cast<double>()).colwise() + tr.translation;
  return (moved - target.cast<double>()).colwise().norm().mean();
}

}  // namespace facecap
