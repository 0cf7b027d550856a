#include "facecap/refine/albedo.hpp"

#include "facecap/render/shading.hpp"

namespace facecap {

AlbedoEstimator::AlbedoEstimator(const MeshLevel& level, AlbedoOptions options, ComputeDevice device)
    : level_(level),
      options_(options),
      solver_(make_albedo_solver(device, level)),
      data_diag_(Eigen::VectorXd::Zero(level.num_vertices)),
      data_rhs_(Eigen::Matrix3Xd::Zero(3, level.num_vertices)),
      albedo_(Positions::Constant(3, level.num_vertices, 0.5f)) {}

void AlbedoEstimator::initialise_uniform(const VertexSamples& samples) {
  Vec3f mean = Vec3f::Zero();
  int n = 0;
  for (Eigen::Index i = 0; i < samples.colour.cols(); ++i) {
    if (!samples.visible[i]) continue;
    mean += samples.colour.col(i);
    ++n;
  }
  if (n > 0) albedo_.colwise() = mean / float(n);
}

void AlbedoEstimator::clear_data() {
  data_diag_.setZero();
  data_rhs_.setZero();
  frames_ = 0;
}

void AlbedoEstimator::add_frame(const VertexSamples& samples, const Positions& normals, const ShCoeffs& lighting) {
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (!samples.visible[i]) continue;
    const Vec3f v = to_viewer_frame(Vec3f(normals.col(i)));
    const double s = sh_shade(lighting, double(v.x()), double(v.y()), double(v.z()));
    if (s <= 1e-3) continue;  // unlit: says nothing about the albedo
    data_diag_[i] += s * s;
    data_rhs_.col(i) += s * samples.colour.col(i).cast<double>();
  }
  ++frames_;
}

void AlbedoEstimator::solve() {
  const int n = level_.num_vertices;
  const AlbedoChannels b = data_rhs_.transpose();
  const AlbedoChannels start = albedo_.transpose().cast<double>();
  // The smooth prior rho_bar, then eq. 4.10 against it.
  const AlbedoChannels prior = solver_->solve(data_diag_, b, options_.prior_smoothing, AlbedoChannels::Zero(n, 3),
                                              start, options_.pcg_iterations);
  const AlbedoChannels rho =
      solver_->solve(data_diag_, b, options_.laplacian_weight, prior, prior, options_.pcg_iterations);
  albedo_ = rho.cwiseMax(0.0).cwiseMin(2.0).transpose().cast<float>();
}

}  // namespace facecap
