// The albedo estimate (§4.3.2, eq. 4.10) against a known albedo, and its
// conjugate gradients on each device. Needs no face model: a dome of 9,409
// vertices (about the ICT face's coarsest level) seen under three lightings.
#include <gtest/gtest.h>

#include <cmath>

#include "cuda_test_support.hpp"
#include "facecap/refine/albedo.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

namespace {

constexpr int kCells = 96;

// A dome 9.6 cm across, 1 mm between vertices, 30 cm in front of the camera
// (normals from about 0 to 40 degrees off the view), with a smooth albedo that
// differs per channel, and a hole no frame sees.
struct AlbedoCase {
  MeshHierarchy hierarchy;
  Positions points, normals, truth;
  std::vector<bool> in_hole;

  AlbedoCase() {
    const int m = kCells + 1;
    points.resize(3, m * m);
    truth.resize(3, m * m);
    in_hole.assign(m * m, false);
    std::vector<Polygon> polygons;
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x) {
        const float px = 0.1f * (x - kCells / 2.0f), py = 0.1f * (y - kCells / 2.0f);
        const int i = y * m + x;
        points.col(i) = Vec3f(px, py, 30.0f + 0.04f * (px * px + py * py));
        for (int c = 0; c < 3; ++c)
          truth(c, i) = 0.45f + 0.1f * c + 0.15f * std::sin(0.8f * px + c) * std::cos(0.6f * py);
        in_hole[i] = (px - 1.5f) * (px - 1.5f) + (py + 1.0f) * (py + 1.0f) < 0.8f * 0.8f;
      }
    for (int y = 0; y < kCells; ++y)
      for (int x = 0; x < kCells; ++x) {
        const int a = y * m + x;
        Polygon q;
        q.v = {a, a + m, a + m + 1, a + 1};
        polygons.push_back(q);
      }
    HierarchyOptions options;
    options.levels = 1;
    hierarchy = MeshHierarchy::build(polygons, m * m, points, {1000, 0, 0}, options);
    normals = level_normals(level(), points);
  }

  const MeshLevel& level() const { return hierarchy.level(0); }

  // Frame f's light: ambient with a directional part turning around the view axis.
  static ShCoeffs lighting(int f) {
    const double angle = 2.1 * f;
    ShCoeffs l = ShCoeffs::Zero();
    l << 0.8, 0.3 * std::cos(angle), 0.25, 0.3 * std::sin(angle), 0.02, 0.0, 0.03, 0.0, 0.01;
    return l;
  }

  // What the camera sees: rho_ic times the shading, outside the hole.
  VertexSamples samples(const ShCoeffs& l) const {
    VertexSamples s;
    s.colour.resize(3, points.cols());
    s.visible.assign(points.cols(), false);
    for (Eigen::Index i = 0; i < points.cols(); ++i) {
      const Vec3f v = to_viewer_frame(Vec3f(normals.col(i)));
      s.colour.col(i) = truth.col(i) * float(sh_shade(l, double(v.x()), double(v.y()), double(v.z())));
      s.visible[i] = !in_hole[i];
      s.visible_count += s.visible[i];
    }
    return s;
  }

  Positions estimate(ComputeDevice device, int frames) const {
    AlbedoOptions options;
    options.frames = frames;
    AlbedoEstimator estimator(level(), options, device);
    estimator.initialise_uniform(samples(lighting(0)));
    for (int f = 0; f < frames; ++f) estimator.add_frame(samples(lighting(f)), normals, lighting(f));
    estimator.solve();
    EXPECT_TRUE(estimator.fixed());
    return estimator.albedo();
  }
};

}  // namespace

// With the true lighting, the albedo comes back where it is seen, each channel
// its own, and the unseen hole is filled smoothly from around it.
TEST(AlbedoEstimator, RecoversAKnownAlbedoAndFillsWhatNoFrameSaw) {
  const AlbedoCase c;
  const Positions albedo = c.estimate(ComputeDevice::cpu, 3);
  ASSERT_TRUE(albedo.allFinite());
  double seen_max = 0, seen_sum = 0, hole_max = 0;
  int seen = 0;
  for (Eigen::Index i = 0; i < albedo.cols(); ++i) {
    const double error = (albedo.col(i) - c.truth.col(i)).cwiseAbs().maxCoeff();
    if (c.in_hole[i]) {
      hole_max = std::max(hole_max, error);
    } else {
      seen_max = std::max(seen_max, error);
      seen_sum += error;
      ++seen;
    }
  }
  // Measured: 2.9e-5 mean, 1.2e-3 at worst (next to the hole, where the
  // Laplacian term pulls hardest), 1.4e-3 in the hole.
  EXPECT_LT(seen_sum / seen, 2e-4);
  EXPECT_LT(seen_max, 5e-3);
  // The hole's truth varies by about 0.2 across it; its fill follows it.
  EXPECT_LT(hole_max, 1e-2);
}

// The same system solved by the CPU reference and by the GPU: the GPU sums in
// another order and contracts multiply-adds, so the results agree to a
// stated tolerance, not to the bit.
TEST(AlbedoSolverOnEachDevice, CudaSolvesWhatTheCpuSolves) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const AlbedoCase c;
  const int n = c.level().num_vertices;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  AlbedoChannels b = AlbedoChannels::Zero(n, 3);
  for (int f = 0; f < 3; ++f) {
    const VertexSamples s = c.samples(AlbedoCase::lighting(f));
    for (int i = 0; i < n; ++i) {
      if (!s.visible[i]) continue;
      const Vec3f v = to_viewer_frame(Vec3f(c.normals.col(i)));
      const double shade = sh_shade(AlbedoCase::lighting(f), double(v.x()), double(v.y()), double(v.z()));
      d[i] += shade * shade;
      b.row(i) += shade * s.colour.col(i).cast<double>().transpose();
    }
  }
  const auto cpu = make_albedo_solver(ComputeDevice::cpu, c.level());
  const auto gpu = make_albedo_solver(ComputeDevice::cuda, c.level());
  const AlbedoChannels start = AlbedoChannels::Constant(n, 3, 0.5);
  // The smooth prior (strong Laplacian, far from converged in 100 iterations), then the estimate against it.
  const AlbedoChannels prior_cpu = cpu->solve(d, b, 50.0, AlbedoChannels::Zero(n, 3), start, 100);
  const AlbedoChannels prior_gpu = gpu->solve(d, b, 50.0, AlbedoChannels::Zero(n, 3), start, 100);
  EXPECT_LT((prior_cpu - prior_gpu).cwiseAbs().maxCoeff(), 1e-6);
  const AlbedoChannels rho_cpu = cpu->solve(d, b, 0.5, prior_cpu, prior_cpu, 100);
  const AlbedoChannels rho_gpu = gpu->solve(d, b, 0.5, prior_cpu, prior_cpu, 100);
  EXPECT_LT((rho_cpu - rho_gpu).cwiseAbs().maxCoeff(), 1e-6);
  // Zero iterations return the start: nothing but the copies.
  EXPECT_EQ(gpu->solve(d, b, 0.5, prior_cpu, start, 0), start);
  // And the whole estimate, through AlbedoEstimator on each device.
  const Positions on_cpu = c.estimate(ComputeDevice::cpu, 3), on_gpu = c.estimate(ComputeDevice::cuda, 3);
  EXPECT_LT((on_cpu - on_gpu).cwiseAbs().maxCoeff(), 1e-5f);
}

}  // namespace facecap
