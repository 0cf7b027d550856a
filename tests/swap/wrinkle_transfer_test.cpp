#include "facecap/swap/wrinkle_transfer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "swap/square_grid.hpp"

namespace facecap {

namespace {

constexpr int kN = 24;  // grid cells per side

// A gently curved sheet; `bump` adds a furrow along x in the middle.
Positions sheet(float curvature, float bump) {
  Positions p(3, (kN + 1) * (kN + 1));
  for (int y = 0; y <= kN; ++y) {
    for (int x = 0; x <= kN; ++x) {
      const float u = float(x) / kN - 0.5f, v = float(y) / kN - 0.5f;
      const float furrow = bump * std::exp(-std::pow((v - 0.1f) / 0.05f, 2.0f)) * std::exp(-std::pow(u / 0.3f, 2.0f));
      p.col(y * (kN + 1) + x) = Vec3f(10 * u, 10 * v, curvature * (u * u + v * v) + furrow);
    }
  }
  return p;
}

}  // namespace

TEST(CoatingTransfer, NoCoatingGivesTheBase) {
  const CoatingTransfer t(test::square_grid(kN), (kN + 1) * (kN + 1));
  const Positions base = sheet(2.0f, 0.0f);
  const Positions out = t.solve(base, Positions::Zero(3, base.cols()));
  EXPECT_LT((out - base).cwiseAbs().maxCoeff(), 1e-4f);
}

TEST(CoatingTransfer, AFurrowMovesOntoAnotherShape) {
  const CoatingTransfer t(test::square_grid(kN), (kN + 1) * (kN + 1), 1e-7);  // next to no anchor: eq. 6.1 exactly
  // The target's furrow, as the coating of its fine mesh over its coarse one...
  const Positions coating = t.coating(sheet(1.0f, -0.3f), sheet(1.0f, 0.0f));
  // ...laid on a differently curved source face.
  const Positions source_base = sheet(3.0f, 0.0f);
  const Positions out = t.solve(source_base, coating);
  const Positions expected = sheet(3.0f, -0.3f);
  const int centre = (kN / 2 + 2) * (kN + 1) + kN / 2;         // on the furrow (v = 0.083)
  EXPECT_LT(out(2, centre) - source_base(2, centre), -0.15f);  // most of the 0.3 depth arrives
  // Up to a translation of the whole sheet (the Laplacian cannot see one; the
  // weak anchor leaves the furrow's mean depth spread over the sheet).
  const float shift = (out.row(2) - expected.row(2)).mean();
  EXPECT_LT(std::abs(shift), 0.02f);
  double err = 0, depth = 0;
  for (Eigen::Index v = 0; v < out.cols(); ++v) {
    err += std::abs(out(2, v) - shift - expected(2, v));
    depth += std::abs(expected(2, v) - source_base(2, v));
  }
  EXPECT_LT(err, 0.2 * depth);  // the shape of the furrow, not noise
}

TEST(CoatingTransfer, SolvesItsLeastSquaresProblem) {
  // ||L x - (L base + coating)||^2 + mu ||x - base||^2, solved densely in
  // double precision with L the uniform graph Laplacian of the grid.
  const std::vector<Triangle> triangles = test::square_grid(kN);
  const int n = (kN + 1) * (kN + 1);
  const double mu = 0.01;
  const CoatingTransfer t(triangles, n, mu);
  const VertexAdjacency adj = vertex_adjacency(triangles, n);
  Eigen::MatrixXd l = Eigen::MatrixXd::Identity(n, n);
  for (int v = 0; v < n; ++v)
    for (int k = adj.offsets[v]; k < adj.offsets[v + 1]; ++k) l(v, adj.indices[k]) = -1.0 / adj.degree(v);
  const Positions base = sheet(2.0f, 0.0f);
  Positions coating = t.coating(sheet(2.0f, -0.3f), base);
  // Some tangential coating too.
  coating.row(0) += 0.01f * Eigen::RowVectorXf::LinSpaced(n, -1.0f, 1.0f);
  coating.row(1) += 0.01f * Eigen::RowVectorXf::LinSpaced(n, 0.0f, 20.0f).array().sin().matrix();
  const Eigen::MatrixXd b = base.transpose().cast<double>();
  const Eigen::MatrixXd rhs = l.transpose() * (l * b + coating.transpose().cast<double>()) + mu * b;
  const Eigen::MatrixXd expected = (l.transpose() * l + mu * Eigen::MatrixXd::Identity(n, n)).ldlt().solve(rhs);
  const Eigen::MatrixXd displacement = expected - b;
  const Eigen::MatrixXd got = t.solve(base, coating).transpose().cast<double>();
  // Within single precision of the largest displacement (0.3 cm here) and
  // of the positions it is added to (up to 5 cm).
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-4 * displacement.cwiseAbs().maxCoeff() + 5 * 2.4e-7);
  // Every coordinate moves as it should, not only the depth.
  for (int k = 0; k < 3; ++k) EXPECT_GT(displacement.col(k).cwiseAbs().maxCoeff(), 1e-4) << k;
}

TEST(CoatingTransfer, RotationTakesOneNormalToTheOther) {
  Positions vectors(3, 1), from(3, 1), to(3, 1);
  vectors.col(0) = Vec3f(0, 0, 2);
  from.col(0) = Vec3f(0, 0, 1);
  to.col(0) = Vec3f(1, 0, 0);
  const Positions r = rotate_between_normals(vectors, from, to);
  EXPECT_LT((Vec3f(r.col(0)) - Vec3f(2, 0, 0)).norm(), 1e-5f);
}

TEST(ExpressionReference, KeepsTheFrameNearestTheSourceByMahalanobis) {
  Eigen::VectorXf source(2);
  source << 0.5f, 0.5f;
  ExpressionReference ref(source);
  auto w = [](float a, float b) {
    Eigen::VectorXf v(2);
    v << a, b;
    return v;
  };
  EXPECT_TRUE(ref.offer(w(0.0f, 0.0f)));   // the first frame is the reference
  EXPECT_FALSE(ref.offer(w(0.0f, 1.0f)));  // no nearer
  EXPECT_TRUE(ref.offer(w(0.45f, 0.5f)));  // nearer
  EXPECT_FALSE(ref.offer(w(0.9f, 0.9f)));
  // Weight 0 varies much more than weight 1 over these frames, so a step
  // along it counts for less than the same step along weight 1.
  for (int i = 0; i < 20; ++i) ref.offer(w(i % 2 ? 0.0f : 1.0f, 0.5f));
  EXPECT_LT(ref.distance(w(0.7f, 0.5f)), ref.distance(w(0.5f, 0.7f)));
}

}  // namespace facecap
