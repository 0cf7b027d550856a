#include "facecap/refine/displacement_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bump_case.hpp"

namespace facecap {

using test::BumpCase;

// Shape from shading on a controlled case: with the regularisers nearly off,
// Gauss-Newton with matrix-free PCG puts the bump back.
TEST(DisplacementSolver, RecoversABumpFromItsShading) {
  const BumpCase c;
  DisplacementOptions o;
  o.gauss_newton_steps = 20;
  o.pcg_iterations = 30;
  o.weights.coarse = 1e-3;
  o.weights.smooth = 1e-3;
  o.data_huber = 0;
  Eigen::VectorXf d;
  double before = 0;
  DisplacementReport rep;
  const double after = c.solve(o, d, before, rep);
  EXPECT_LT(rep.final_cost, 0.05 * rep.initial_cost);
  EXPECT_LT(after, 0.25 * before);
  EXPECT_GT(d.cast<double>().normalized().dot(c.truth.cast<double>().normalized()), 0.9);
  EXPECT_NEAR(d.maxCoeff(), c.truth.maxCoeff(), 0.3 * c.truth.maxCoeff());
  EXPECT_TRUE(d.allFinite());
}

// With the paper's weights and iteration counts (10 steps, 7 iterations) the
// regularisers hold the bump back, but it moves the surface toward the truth.
TEST(DisplacementSolver, PaperWeightsMoveTowardTheTruth) {
  const BumpCase c;
  Eigen::VectorXf d;
  double before = 0;
  DisplacementReport rep;
  const double after = c.solve(DisplacementOptions{}, d, before, rep);
  EXPECT_LT(rep.final_cost, rep.initial_cost);
  EXPECT_LT(after, 0.8 * before);
  EXPECT_GT(d.cast<double>().normalized().dot(c.truth.cast<double>().normalized()), 0.8);
}

// The paper's 10 Gauss-Newton steps of 7 PCG iterations reach the energy's
// minimum: running far longer lowers it by under 1%. (A normal operator that
// disagrees with the gradient, as one with unscaled regulariser weights
// did, damps every step and stops well short.)
TEST(DisplacementSolver, PaperIterationsReachTheEnergysMinimum) {
  const BumpCase c;
  Eigen::VectorXf d_paper, d_long;
  double before = 0;
  DisplacementReport paper, longer;
  c.solve(DisplacementOptions{}, d_paper, before, paper, true);
  DisplacementOptions o;
  o.gauss_newton_steps = 60;
  o.pcg_iterations = 60;
  o.function_tolerance = 0;  // to the end
  c.solve(o, d_long, before, longer, true);
  EXPECT_LT(longer.final_cost, paper.initial_cost);
  EXPECT_LT(paper.final_cost - longer.final_cost, 0.01 * (paper.initial_cost - longer.final_cost));
  EXPECT_LT((d_paper - d_long).norm(), 0.05 * d_long.norm());
}

// The convergence test stops Gauss-Newton once its model promises less than
// function_tolerance of the energy: here after fewer steps than 60, at the
// energy of running all 60 (a wrong predicted decrease would stop at once, or
// never).
TEST(DisplacementSolver, ConvergenceTestStopsAtTheSameEnergy) {
  const BumpCase c;
  Eigen::VectorXf d_tol, d_all;
  double before = 0;
  DisplacementReport tol, all;
  DisplacementOptions o;
  o.gauss_newton_steps = 60;
  o.function_tolerance = 1e-6;
  c.solve(o, d_tol, before, tol, true);
  o.function_tolerance = 0;
  c.solve(o, d_all, before, all, true);
  EXPECT_TRUE(tol.converged);
  EXPECT_GE(tol.steps, 2);
  EXPECT_LT(tol.steps, 60);
  EXPECT_LT(tol.final_cost - all.final_cost, 1e-4 * (all.initial_cost - all.final_cost));
  EXPECT_LT((d_tol - d_all).norm(), 0.01 * d_all.norm());
}

}  // namespace facecap
