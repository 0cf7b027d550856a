#include "facecap/refine/albedo.hpp"

#include "facecap/render/shading.hpp"

namespace facecap {

AlbedoEstimator::AlbedoEstimator(const MeshLevel& level, AlbedoOptions options)
    : level_(level),
      options_(options),
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

Eigen::VectorXd AlbedoEstimator::laplacian_normal(const Eigen::VectorXd& x) const {
  // L = I - A / r (uniform graph Laplacian); returns L^T (L x).
  const VertexAdjacency& r = level_.rings;
  const int n = level_.num_vertices;
  Eigen::VectorXd lx(n);
  for (int i = 0; i < n; ++i) {
    double mean = 0;
    const int deg = r.degree(i);
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) mean += x[r.indices[s]];
    lx[i] = deg > 0 ? x[i] - mean / deg : 0.0;
  }
  Eigen::VectorXd out = lx;
  for (int i = 0; i < n; ++i) {
    const int deg = r.degree(i);
    if (deg == 0) continue;
    for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) out[r.indices[s]] -= lx[i] / deg;
  }
  return out;
}

Eigen::VectorXd AlbedoEstimator::solve_channel(const Eigen::VectorXd& d, const Eigen::VectorXd& b, double w,
                                               const Eigen::VectorXd& prior, Eigen::VectorXd x) const {
  const int n = level_.num_vertices;
  // Jacobi preconditioner: diag(D + w L^T L) = D_i + w (1 + sum_{j in ring(i)} 1/r_j^2).
  Eigen::VectorXd diag = d;
  const VertexAdjacency& r = level_.rings;
  for (int i = 0; i < n; ++i) {
    double s = 1.0;
    for (int k = r.offsets[i]; k < r.offsets[i + 1]; ++k) {
      const int deg = r.degree(r.indices[k]);
      if (deg > 0) s += 1.0 / (double(deg) * deg);
    }
    diag[i] += w * s;
  }
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return d.cwiseProduct(v) + w * laplacian_normal(v); };
  const Eigen::VectorXd rhs = b + w * laplacian_normal(prior);
  Eigen::VectorXd res = rhs - apply(x);
  Eigen::VectorXd z = res.cwiseQuotient(diag);
  Eigen::VectorXd p = z;
  double rz = res.dot(z);
  for (int k = 0; k < options_.pcg_iterations && rz > 1e-20; ++k) {
    const Eigen::VectorXd ap = apply(p);
    const double alpha = rz / p.dot(ap);
    x += alpha * p;
    res -= alpha * ap;
    z = res.cwiseQuotient(diag);
    const double rz_new = res.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  return x;
}

void AlbedoEstimator::solve() {
  const int n = level_.num_vertices;
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd b = data_rhs_.row(c).transpose();
    const Eigen::VectorXd start = albedo_.row(c).transpose().cast<double>();
    // The smooth prior rho_bar, then eq. 4.10 against it.
    const Eigen::VectorXd prior =
        solve_channel(data_diag_, b, options_.prior_smoothing, Eigen::VectorXd::Zero(n), start);
    const Eigen::VectorXd rho = solve_channel(data_diag_, b, options_.laplacian_weight, prior, prior);
    albedo_.row(c) = rho.cwiseMax(0.0).cwiseMin(2.0).transpose().cast<float>();
  }
}

}  // namespace facecap
