#pragma once
// Wrinkle prediction (§6.1.2): the target's fine-scale motion is carried
// onto the swapped face by Laplacian coating transfer.
//   coating       xi = L(M) - L(M~)            (fine mesh over its coarse base)
//   motion        D_t = xi_t^T - xi_0^T        (against a reference frame)
//   eq. 6.1       M_t^S = L^-1(L(M~_t^S) + xi_0^S + R(D_t))
// with R the per-vertex rotation between the tangent frames of the coarse
// target and swapped meshes, and the reference frame the one whose
// expression is nearest the source's by the squared Mahalanobis distance of
// eq. 6.2 (updated while a nearer frame appears). The inverse Laplacian is a
// least-squares solve, ||L x - delta||^2 + mu ||x - M~||^2, whose matrix is
// factorised once (sparse LDLT).
#include <memory>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

// Eq. 6.2's reference frame. ICT ships no expression covariance, so it is
// estimated from the target's tracked weights as they arrive (the sample
// covariance plus a ridge of 0.01 per weight, which keeps it invertible over
// the first frames and for weights the target never moves).
class ExpressionReference {
 public:
  explicit ExpressionReference(Eigen::VectorXf source_expression, double ridge = 0.01);
  // Adds a frame to the covariance estimate; true when it is now the reference
  // (the first frame, or nearer the source than the reference so far).
  bool offer(const Eigen::VectorXf& weights);
  double distance(const Eigen::VectorXf& weights) const;  // squared Mahalanobis to the source's
  const Eigen::VectorXf& reference() const { return reference_; }

 private:
  Eigen::VectorXd source_;
  double ridge_;
  Eigen::VectorXd sum_;
  Eigen::MatrixXd outer_;
  int count_ = 0;
  Eigen::VectorXf reference_;
};

class CoatingTransfer {
 public:
  // anchor_weight: mu, small: it pins the solve's null space (translation)
  // and lets the smoothest part of a coating fade rather than bend the face.
  CoatingTransfer(const std::vector<Triangle>& triangles, int num_vertices, double anchor_weight = 0.01);
  ~CoatingTransfer();
  CoatingTransfer(CoatingTransfer&&) noexcept;
  CoatingTransfer& operator=(CoatingTransfer&&) noexcept;

  Positions laplacian(const Positions& points) const;  // uniform graph Laplacian, per vertex
  // L(fine) - L(base), as L(fine - base): one product, without the
  // cancellation of two positions' Laplacians.
  Positions coating(const Positions& fine, const Positions& base) const { return laplacian(fine - base); }
  // Eq. 6.1: the mesh whose Laplacian is L(base) + coating, anchored softly to base.
  Positions solve(const Positions& base, const Positions& coating) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Rotates each vertex's vector by the smallest rotation taking `from`'s unit
// normal to `to`'s (the tangent-frame rotation R of eq. 6.1).
Positions rotate_between_normals(const Positions& vectors, const Positions& from, const Positions& to);

}  // namespace facecap
