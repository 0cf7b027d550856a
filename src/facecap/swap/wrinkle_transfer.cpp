#include "facecap/swap/wrinkle_transfer.hpp"

#include <Eigen/SparseCholesky>

#include "facecap/core/error.hpp"

namespace facecap {

ExpressionReference::ExpressionReference(Eigen::VectorXf source_expression, double ridge)
    : source_(source_expression.cast<double>()),
      ridge_(ridge),
      sum_(Eigen::VectorXd::Zero(source_.size())),
      outer_(Eigen::MatrixXd::Zero(source_.size(), source_.size())) {}

double ExpressionReference::distance(const Eigen::VectorXf& weights) const {
  const Eigen::Index n = source_.size();
  Eigen::MatrixXd c = ridge_ * Eigen::MatrixXd::Identity(n, n);
  if (count_ > 1) {
    const Eigen::VectorXd mean = sum_ / count_;
    c += (outer_ - count_ * mean * mean.transpose()) / (count_ - 1);
  }
  const Eigen::VectorXd d = weights.cast<double>() - source_;
  return d.dot(c.ldlt().solve(d));
}

bool ExpressionReference::offer(const Eigen::VectorXf& weights) {
  const Eigen::VectorXd w = weights.cast<double>();
  sum_ += w;
  outer_ += w * w.transpose();
  ++count_;
  // Both under the covariance as it stands now: it changes with every frame.
  if (count_ == 1 || distance(weights) < distance(reference_)) {
    reference_ = weights;
    return true;
  }
  return false;
}

struct CoatingTransfer::Impl {
  Eigen::SparseMatrix<double> laplacian;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  double anchor = 0;
};

CoatingTransfer::CoatingTransfer(const std::vector<Triangle>& triangles, int num_vertices, double anchor_weight)
    : impl_(std::make_unique<Impl>()) {
  const VertexAdjacency adj = vertex_adjacency(triangles, num_vertices);
  std::vector<Eigen::Triplet<double>> t;
  for (int v = 0; v < num_vertices; ++v) {
    const int degree = adj.degree(v);
    if (degree == 0) continue;
    t.emplace_back(v, v, 1.0);
    for (int k = adj.offsets[v]; k < adj.offsets[v + 1]; ++k) t.emplace_back(v, adj.indices[k], -1.0 / degree);
  }
  Eigen::SparseMatrix<double>& l = impl_->laplacian;
  l.resize(num_vertices, num_vertices);
  l.setFromTriplets(t.begin(), t.end());
  impl_->anchor = anchor_weight;
  Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(l.transpose()) * l;
  for (int v = 0; v < num_vertices; ++v) normal.coeffRef(v, v) += anchor_weight;
  impl_->solver.compute(normal);
  if (impl_->solver.info() != Eigen::Success)
    throw Error("wrinkle transfer: the mesh Laplacian could not be factorised");
}

CoatingTransfer::~CoatingTransfer() = default;
CoatingTransfer::CoatingTransfer(CoatingTransfer&&) noexcept = default;
CoatingTransfer& CoatingTransfer::operator=(CoatingTransfer&&) noexcept = default;

Positions CoatingTransfer::laplacian(const Positions& points) const {
  const Eigen::MatrixXd x = points.transpose().cast<double>();
  return (impl_->laplacian * x).transpose().cast<float>();
}

Positions CoatingTransfer::solve(const Positions& base, const Positions& coating) const {
  // Normal equations of ||L x - (L base + coating)||^2 + mu ||x - base||^2.
  const Eigen::MatrixXd b = base.transpose().cast<double>();
  const Eigen::MatrixXd delta = impl_->laplacian * b + coating.transpose().cast<double>();
  const Eigen::MatrixXd rhs = Eigen::SparseMatrix<double>(impl_->laplacian.transpose()) * delta + impl_->anchor * b;
  const Eigen::MatrixXd x = impl_->solver.solve(rhs);
  return x.transpose().cast<float>();
}

Positions rotate_between_normals(const Positions& vectors, const Positions& from, const Positions& to) {
  Positions out(3, vectors.cols());
  for (Eigen::Index v = 0; v < vectors.cols(); ++v) {
    const Vec3f a = from.col(v), b = to.col(v);
    if (a.squaredNorm() < 1e-12f || b.squaredNorm() < 1e-12f) {
      out.col(v) = vectors.col(v);
      continue;
    }
    out.col(v) = Eigen::Quaternionf::FromTwoVectors(a, b) * Vec3f(vectors.col(v));
  }
  return out;
}

}  // namespace facecap
