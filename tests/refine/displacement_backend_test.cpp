#include "facecap/refine/displacement_backend.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "bump_case.hpp"
#include "cuda_test_support.hpp"
#include "facecap/refine/displacement_bench.hpp"
#include "facecap/refine/displacement_problem_io.hpp"

namespace facecap {

using test::BumpCase;

namespace {

struct Solved {
  Eigen::VectorXf d;
  DisplacementReport report;
};

Solved solve_on(DisplacementBackend& backend, const DisplacementProblem& problem, const Eigen::VectorXf& start,
                const DisplacementOptions& options) {
  Solved s{start, {}};
  s.report = backend.solve(problem, s.d, options);
  return s;
}

// The CUDA result against the CPU reference: the same steps, the same energy
// to a part in 10^5 and the same displacements to 0.1 % of their largest.
void expect_same_solve(const Solved& cpu, const Solved& gpu) {
  EXPECT_EQ(gpu.report.steps, cpu.report.steps);
  EXPECT_EQ(gpu.report.converged, cpu.report.converged);
  EXPECT_NEAR(gpu.report.initial_cost, cpu.report.initial_cost, 1e-5 * cpu.report.initial_cost);
  EXPECT_NEAR(gpu.report.final_cost, cpu.report.final_cost, 1e-5 * cpu.report.initial_cost);
  ASSERT_EQ(gpu.d.size(), cpu.d.size());
  const float largest = cpu.d.cwiseAbs().maxCoeff();
  EXPECT_GT(largest, 0.0f);
  EXPECT_LT((gpu.d - cpu.d).cwiseAbs().maxCoeff(), 1e-3f * largest);
  EXPECT_TRUE(gpu.d.allFinite());
}

// The bump's colours with noise, so that the Huber weights take effect.
VertexSamples noisy(const VertexSamples& samples, float sigma, unsigned seed) {
  VertexSamples out = samples;
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  for (Eigen::Index i = 0; i < out.colour.size(); ++i) out.colour.data()[i] += noise(rng);
  return out;
}

}  // namespace

TEST(ComputeDevice, ParsesItsNames) {
  EXPECT_EQ(parse_compute_device("cpu"), ComputeDevice::cpu);
  EXPECT_EQ(parse_compute_device("cuda"), ComputeDevice::cuda);
  EXPECT_FALSE(parse_compute_device("gpu").has_value());
  EXPECT_EQ(to_string(ComputeDevice::cuda), "cuda");
  EXPECT_EQ(default_compute_device(), cuda_device_available() ? ComputeDevice::cuda : ComputeDevice::cpu);
}

TEST(DisplacementBackend, CpuBackendIsTheReferenceSolver) {
  const BumpCase c;
  const DisplacementProblem problem = c.problem(true);
  Eigen::VectorXf reference = Eigen::VectorXf::Zero(c.base.cols());
  const DisplacementReport expected = solve_displacements(problem, reference, {});
  const auto backend = make_displacement_backend(ComputeDevice::cpu);
  const Solved s = solve_on(*backend, problem, Eigen::VectorXf::Zero(c.base.cols()), {});
  EXPECT_EQ(s.report.steps, expected.steps);
  EXPECT_EQ(s.report.final_cost, expected.final_cost);
  EXPECT_EQ(s.d, reference);
}

// Without a GPU (or without the CUDA build) asking for CUDA is a clear error, not a crash.
TEST(DisplacementBackend, CudaWithoutADeviceIsAClearError) {
  if (cuda_device_available()) GTEST_SKIP() << "a CUDA device is present";
  try {
    make_displacement_backend(ComputeDevice::cuda);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--device cpu"), std::string::npos) << e.what();
  }
}

// Every term of eq. 4.12 on (data with Huber weights, smoothness, hierarchy,
// temporal, coarse), the paper's iteration counts.
TEST(CudaDisplacementSolver, MatchesTheCpuOnEveryTerm) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const BumpCase c;
  const VertexSamples samples = noisy(c.samples, 0.03f, 1);
  DisplacementProblem problem = c.problem(true);
  problem.samples = &samples;
  const Eigen::VectorXf start = Eigen::VectorXf::Zero(c.base.cols());
  const auto cpu = make_displacement_backend(ComputeDevice::cpu);
  const auto gpu = make_displacement_backend(ComputeDevice::cuda);
  expect_same_solve(solve_on(*cpu, problem, start, {}), solve_on(*gpu, problem, start, {}));
}

// Only part of the level free (the refiner's active set: d = 0 outside), a
// warm start, occluded vertices, and long solves that run to convergence.
TEST(CudaDisplacementSolver, MatchesTheCpuOnAnActiveSubsetToConvergence) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const BumpCase c;
  VertexSamples samples = noisy(c.samples, 0.01f, 2);
  DisplacementProblem problem = c.problem(true);
  problem.samples = &samples;
  problem.active.assign(c.base.cols(), false);
  for (Eigen::Index i = 0; i < c.base.cols(); ++i) {
    problem.active[i] = c.base.col(i).head<2>().norm() < 1.5f;
    if (c.base(0, i) > 1.0f) samples.visible[i] = false;
  }
  const Eigen::VectorXf start = 0.3f * c.truth;
  DisplacementOptions o;
  o.gauss_newton_steps = 40;
  o.pcg_iterations = 20;
  const auto cpu = make_displacement_backend(ComputeDevice::cpu);
  const auto gpu = make_displacement_backend(ComputeDevice::cuda);
  const Solved reference = solve_on(*cpu, problem, start, o);
  const Solved result = solve_on(*gpu, problem, start, o);
  expect_same_solve(reference, result);
  for (Eigen::Index i = 0; i < c.base.cols(); ++i) {
    if (!problem.active[i]) {
      EXPECT_EQ(result.d[i], 0.0f);
    }
  }
}

// One backend serves frame after frame and level after level: its resident
// topology and buffers must not leak one solve into the next.
TEST(CudaDisplacementSolver, ServesSeveralLevelsAndFrames) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const BumpCase a, b;
  const auto cpu = make_displacement_backend(ComputeDevice::cpu);
  const auto gpu = make_displacement_backend(ComputeDevice::cuda);
  for (int frame = 0; frame < 3; ++frame) {
    for (const BumpCase* c : {&a, &b}) {
      const VertexSamples samples = noisy(c->samples, 0.02f, 10 + frame);
      DisplacementProblem problem = c->problem(frame > 0);
      problem.samples = &samples;
      if (c == &b) problem.active.assign(c->base.cols(), frame != 1);  // frame 1: nothing free
      const Eigen::VectorXf start = Eigen::VectorXf::Zero(c->base.cols());
      const Solved reference = solve_on(*cpu, problem, start, {});
      const Solved result = solve_on(*gpu, problem, start, {});
      if (reference.d.cwiseAbs().maxCoeff() == 0) {
        EXPECT_EQ(result.d.cwiseAbs().maxCoeff(), 0.0f);
        EXPECT_NEAR(result.report.final_cost, reference.report.final_cost, 1e-6 * reference.report.final_cost);
      } else {
        expect_same_solve(reference, result);
      }
    }
  }
}

// Real footage: the problems of a tracked video, saved by `facecap eval
// refine --video V --save-problems DIR` and named by
// FACECAP_DISPLACEMENT_PROBLEMS (they hold no model or footage, so a GPU
// machine can run this without either). Each must agree within the tolerance
// `facecap bench displacement --check` applies.
TEST(CudaDisplacementSolver, MatchesTheCpuOnSavedRealFrames) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const char* dir = std::getenv("FACECAP_DISPLACEMENT_PROBLEMS");
  if (dir == nullptr || *dir == '\0')
    GTEST_SKIP() << "set FACECAP_DISPLACEMENT_PROBLEMS to a folder written by `facecap eval refine --save-problems`";
  const auto cpu = make_displacement_backend(ComputeDevice::cpu);
  const auto gpu = make_displacement_backend(ComputeDevice::cuda);
  int problems = 0;
  DeviceAgreement all;
  for (const auto& p : load_displacement_problems(dir)) {
    const Solved reference = solve_on(*cpu, p->problem, p->start, {});
    const Solved result = solve_on(*gpu, p->problem, p->start, {});
    const DeviceAgreement a = compare_solves(reference.d, reference.report, result.d, result.report);
    EXPECT_TRUE(a.within_tolerance()) << "frame " << p->frame << " level " << p->level_index << ": rel diff "
                                      << a.max_rel_diff << ", cost rel diff " << a.max_cost_rel_diff;
    all = worst(all, a);
    ++problems;
  }
  ASSERT_GT(problems, 0) << "no .fcdp files in " << dir;
  std::printf("%d real problems: largest difference %.3f um (%.2e of the largest d), energy %.2e, same steps %d\n",
              problems, all.max_abs_diff_um, all.max_rel_diff, all.max_cost_rel_diff, all.same_steps);
}

}  // namespace facecap
