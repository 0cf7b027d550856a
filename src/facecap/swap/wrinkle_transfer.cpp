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

namespace {

using Columns3 = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;
// Single precision is enough for L^T L + mu (eigenvalues from mu = 0.01 to
// about 4) solved for a displacement, not a position: on a 33k-vertex sheet
// its largest error is 2.5e-5 of the largest displacement, under the
// rounding of the positions it is added to, and the solve takes 7.8 ms
// instead of 10.3.
using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<float>>;

// Solves P^T L D L^T P x = b for the three columns of b at once, in place,
// with the factor SimplicialLDLT computed (it stores L's columns without the
// unit diagonal, rows in increasing order). Eigen's own solve walks L (4.4M
// entries for the 33k vertices of a 720p face's finest level) once per
// column and direction; with the columns interleaved it walks it twice
// (`swap_bench` BM_CoatingTransferSolve, doubles: 25.0 -> 10.3 ms).
void solve_interleaved(const Ldlt& ldlt, Columns3& x) {
  const Eigen::SparseMatrix<float>& l = ldlt.matrixL().nestedExpression();
  const int n = static_cast<int>(x.rows());
  const int* begin = l.outerIndexPtr();
  const int* row = l.innerIndexPtr();
  const float* value = l.valuePtr();
  Columns3 y = ldlt.permutationP() * x;
  float* v = y.data();
  // L y' = y: column by column, each solved entry subtracted below it.
  for (int i = 0; i < n; ++i) {
    const float a = v[3 * i], b = v[3 * i + 1], c = v[3 * i + 2];
    if (a == 0 && b == 0 && c == 0) continue;
    for (int k = begin[i]; k < begin[i + 1]; ++k) {
      float* r = v + 3 * row[k];
      r[0] -= value[k] * a;
      r[1] -= value[k] * b;
      r[2] -= value[k] * c;
    }
  }
  const Eigen::VectorXf& d = ldlt.vectorD();
  for (int i = 0; i < n; ++i) {
    const float inv = 1.0f / d[i];
    for (int j = 0; j < 3; ++j) v[3 * i + j] = inv * v[3 * i + j];
  }
  // L^T x' = y': row i of L^T is column i of L.
  for (int i = n - 1; i >= 0; --i) {
    float a = v[3 * i], b = v[3 * i + 1], c = v[3 * i + 2];
    for (int k = begin[i]; k < begin[i + 1]; ++k) {
      const float* r = v + 3 * row[k];
      a -= value[k] * r[0];
      b -= value[k] * r[1];
      c -= value[k] * r[2];
    }
    v[3 * i] = a;
    v[3 * i + 1] = b;
    v[3 * i + 2] = c;
  }
  x = ldlt.permutationPinv() * y;
}

}  // namespace

struct CoatingTransfer::Impl {
  Eigen::SparseMatrix<double> laplacian;
  Eigen::SparseMatrix<double> laplacian_transposed;
  Ldlt solver;  // of L^T L + mu
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
  impl_->laplacian_transposed = l.transpose();
  Eigen::SparseMatrix<double> normal = impl_->laplacian_transposed * l;
  for (int v = 0; v < num_vertices; ++v) normal.coeffRef(v, v) += anchor_weight;
  impl_->solver.compute(normal.cast<float>());
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
  // The normal equations of ||L x - (L base + coating)||^2 + mu ||x - base||^2,
  // for the displacement y = x - base: (L^T L + mu) y = L^T coating.
  Columns3 y = (impl_->laplacian_transposed * coating.transpose().cast<double>()).cast<float>();
  solve_interleaved(impl_->solver, y);
  return base + y.transpose();
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
