#pragma once
// Displacement refinement, §4.3.3-4.3.4: per-vertex displacements d along the
// base normals of one hierarchy level,
//   E(d) = E_data + w3 E_smooth + w4 E_hier + w5 E_temp + w6 E_coarse   (eq. 4.12)
// with E_data = sum_i visible sum_c (rho_ic l^T SH(n*_i(d)) - I_ic)^2, the
// displaced normal n*_i(d) = sum over incident triangles of
// ((v_j + d_j n_j) - (v_i + d_i n_i)) x ((v_k + d_k n_k) - (v_i + d_i n_i))
// (eq. 4.11), E_smooth = ||L d||^2 (uniform graph Laplacian), E_hier =
// ||d - pd||^2 (pd prolonged from the coarser level), E_temp = ||d - d_prev||^2,
// E_coarse = ||d||^2, weights 10, 30, 1, 7, and d = 0 on the mesh boundary
// (Dirichlet). Minimised by Gauss-Newton (10 steps, eq. 4.13-4.14), each
// normal equation J^T J dd = -J^T r solved by 7 iterations of Jacobi-
// preconditioned conjugate gradients (Algorithm 2) with J^T J never formed:
// products J^T (J p) are evaluated from per-vertex shading derivatives.
//
// Units: positions and d in centimetres, intensities in [0, 1].
#include <Eigen/Core>
#include <vector>

#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/refine/vertex_samples.hpp"

namespace facecap {

struct DisplacementWeights {
  double smooth = 10.0;     // w3
  double hierarchy = 30.0;  // w4
  double temporal = 1.0;    // w5
  double coarse = 7.0;      // w6
};

struct DisplacementOptions {
  DisplacementWeights weights;
  // The paper's weights were set for FaceWarehouse's mesh units, not for
  // centimetres. Displacements are measured in this unit for the quadratic
  // terms (each weight divided by its square). FaceWarehouse's unit is about
  // 10 cm (a face spans roughly 1.6 units), but with the energy minimised
  // exactly, 10 lets image noise and albedo texture into flat skin: on
  // `eval refine --synthetic 12`, seeds 1-4, the refined normal error is
  // 1.30 deg (seed 2) at 10, 0.85 at 5, 0.78 at 4 and 0.72 at 3, against
  // 0.64 for the coarse mesh; address_720p_a's refined photometric error is
  // 4.54 / 4.72 / 4.77 / 4.82. 4 keeps wrinkles on real footage and flat
  // skin flat; the synthetic renders' lighting shows wrinkles faintly, so
  // their normals alone would always ask for more smoothing.
  double length_unit_cm = 4.0;
  // Huber scale of the per-vertex photometric residual (intensity, 0-1):
  // albedo detail finer than the coarse mesh, highlights and noise should not
  // become geometry. 0 = plain least squares.
  double data_huber = 0.02;
  int gauss_newton_steps = 10;
  int pcg_iterations = 7;
  // Converged: Gauss-Newton stops when its model predicts a relative decrease
  // of the energy below this (Ceres' function_tolerance). On refine_bench's
  // frames every step that then failed to lower the energy (four halvings,
  // four wasted linearisations) had a predicted decrease below 4e-7 of the
  // energy, median 4e-8; accepted steps' median was 2e-5.
  double function_tolerance = 1e-6;
};

struct DisplacementProblem {
  const MeshLevel* level = nullptr;
  Positions base;          // camera-space positions of the level (cm)
  Positions base_normals;  // unit vertex normals of the base surface
  Positions albedo;        // RGB per vertex
  ShCoeffs lighting = ShCoeffs::Zero();
  const VertexSamples* samples = nullptr;
  Eigen::VectorXf prolonged;  // pd: from the coarser level (empty at level 0: no E_hier)
  Eigen::VectorXf previous;   // d of the previous frame (empty: no E_temp)
  // Vertices solved for (empty: all but the boundary). Others hold d = 0:
  // the refinement solves only where the camera sees skin (and a margin).
  std::vector<bool> active;
};

struct DisplacementReport {
  double initial_cost = 0;
  double final_cost = 0;
  int steps = 0;           // Gauss-Newton steps taken
  bool converged = false;  // stopped by function_tolerance
  // Milliseconds spent before the first Gauss-Newton step: the solve's graph
  // of free and touched vertices and, on a GPU, the frame's upload.
  double setup_ms = 0;
};

DisplacementReport solve_displacements(const DisplacementProblem& problem, Eigen::VectorXf& d,
                                       const DisplacementOptions& options = {});

// The displaced surface v + d n and its normals (eq. 4.11).
Positions displaced_positions(const Positions& base, const Positions& normals, const Eigen::VectorXf& d);

}  // namespace facecap
