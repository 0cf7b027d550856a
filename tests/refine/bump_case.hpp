#pragma once
// A controlled displacement problem for the solver's tests.
#include <algorithm>
#include <cmath>

#include "facecap/refine/displacement_solver.hpp"
#include "facecap/render/shading.hpp"

namespace facecap::test {

// A flat patch seen from the front, lit from the side and above, 1 mm
// between vertices; the image is rendered from a Gaussian bump 0.5 mm high
// and 3 mm wide. The solver gets the flat patch.
struct BumpCase {
  MeshHierarchy hierarchy;
  Positions base, normals, true_normals, albedo;
  Eigen::VectorXf truth;
  ShCoeffs lighting;
  VertexSamples samples;

  BumpCase() {
    const int n = 40;
    std::vector<Polygon> polys;
    base.resize(3, (n + 1) * (n + 1));
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x)
        base.col(y * (n + 1) + x) = Vec3f(0.1f * (x - n / 2.0f), 0.1f * (y - n / 2.0f), 30.0f);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        Polygon q;
        const int a = y * (n + 1) + x;
        q.v = {a, a + n + 1, a + n + 2, a + 1};
        polys.push_back(q);
      }
    }
    HierarchyOptions ho;
    ho.levels = 1;
    hierarchy = MeshHierarchy::build(polys, static_cast<int>(base.cols()), base, {1000, 0, 0}, ho);
    normals = level_normals(level(), base);
    truth.resize(base.cols());
    for (Eigen::Index i = 0; i < base.cols(); ++i) {
      const float r2 = base(0, i) * base(0, i) + base(1, i) * base(1, i);
      truth[i] = 0.05f * std::exp(-r2 / (2 * 0.3f * 0.3f));
    }
    true_normals = level_normals(level(), displaced_positions(base, normals, truth));
    lighting = ShCoeffs::Zero();
    lighting[0] = 0.6;
    lighting[1] = 0.35;
    lighting[2] = 0.25;
    lighting[3] = 0.5;
    albedo = Positions::Constant(3, base.cols(), 0.7f);
    samples.colour.resize(3, base.cols());
    samples.visible.assign(base.cols(), true);
    for (Eigen::Index i = 0; i < base.cols(); ++i) {
      const Vec3f v = to_viewer_frame(Vec3f(true_normals.col(i)));
      samples.colour.col(i) = albedo.col(i) * sh_shade(lighting, v.x(), v.y(), v.z());
    }
  }
  const MeshLevel& level() const { return hierarchy.level(0); }

  // The solve of this case; with_previous adds a previous frame's and a
  // coarser level's displacements, so that every term of the energy is on.
  DisplacementProblem problem(bool with_previous = false) const {
    DisplacementProblem problem;
    if (with_previous) {
      problem.previous = 0.5f * truth;
      problem.prolonged = Eigen::VectorXf::Zero(truth.size());
    }
    problem.level = &level();
    problem.base = base;
    problem.base_normals = normals;
    problem.albedo = albedo;
    problem.lighting = lighting;
    problem.samples = &samples;
    return problem;
  }

  // Solves; returns the summed normal error (radians) after, and sets `before`.
  double solve(const DisplacementOptions& o, Eigen::VectorXf& d, double& before, DisplacementReport& rep,
               bool with_previous = false) const {
    d = Eigen::VectorXf::Zero(base.cols());
    rep = solve_displacements(problem(with_previous), d, o);
    const Positions refined = level_normals(level(), displaced_positions(base, normals, d));
    double after = 0;
    before = 0;
    for (Eigen::Index i = 0; i < base.cols(); ++i) {
      if (level().boundary[i]) continue;
      before += std::acos(std::clamp(double(normals.col(i).dot(true_normals.col(i))), -1.0, 1.0));
      after += std::acos(std::clamp(double(refined.col(i).dot(true_normals.col(i))), -1.0, 1.0));
    }
    return after;
  }
};

}  // namespace facecap::test
