// The displacement solve alone (§4.3.4) on saved real-footage problems, per
// device and level: `facecap eval refine --video V --save-problems DIR`
// writes them, and FACECAP_DISPLACEMENT_PROBLEMS=DIR points this program at
// them. One iteration is one problem's solve (the paper's 10 Gauss-Newton
// steps of 7 PCG iterations, or fewer once converged), cycling over the
// saved frames. The CUDA benchmarks appear where a GPU answers.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "facecap/core/allocator_tuning.hpp"
#include "facecap/refine/displacement_backend.hpp"
#include "facecap/refine/displacement_problem_io.hpp"

namespace facecap {

namespace {

using Problems = std::vector<std::unique_ptr<SavedDisplacementProblem>>;

void solve_level(benchmark::State& state, ComputeDevice device, const Problems* problems) {
  const std::unique_ptr<DisplacementBackend> backend = make_displacement_backend(device);
  size_t next = 0;
  long steps = 0, solves = 0;
  double setup_ms = 0;
  for (auto _ : state) {
    const SavedDisplacementProblem& p = *(*problems)[next];
    next = (next + 1) % problems->size();
    Eigen::VectorXf d = p.start;
    const DisplacementReport report = backend->solve(p.problem, d, {});
    steps += report.steps;
    setup_ms += report.setup_ms;
    ++solves;
    benchmark::DoNotOptimize(d.data());
  }
  const auto& active = problems->front()->problem.active;
  state.counters["free_vertices"] =
      double(active.empty() ? problems->front()->level.num_vertices : std::count(active.begin(), active.end(), true));
  state.counters["gauss_newton_steps"] = double(steps) / double(std::max(1L, solves));
  state.counters["setup_ms"] = setup_ms / double(std::max(1L, solves));
}

}  // namespace

}  // namespace facecap

int main(int argc, char** argv) {
  using namespace facecap;
  keep_large_allocations_resident();  // as facecap's own main does
  benchmark::Initialize(&argc, argv);
  const char* dir = std::getenv("FACECAP_DISPLACEMENT_PROBLEMS");
  if (dir == nullptr || *dir == '\0') {
    std::fprintf(stderr,
                 "displacement_bench: set FACECAP_DISPLACEMENT_PROBLEMS to a folder written by "
                 "`facecap eval refine --video V --save-problems DIR`\n");
    return 2;
  }
  static std::map<int, Problems> by_level;
  try {
    for (auto& p : load_displacement_problems(dir)) by_level[p->level_index].push_back(std::move(p));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "displacement_bench: %s\n", e.what());
    return 2;
  }
  std::vector<ComputeDevice> devices{ComputeDevice::cpu};
  if (cuda_device_available()) devices.push_back(ComputeDevice::cuda);
  for (ComputeDevice device : devices)
    for (auto& [level, problems] : by_level) {
      const std::string name =
          "BM_DisplacementSolve/" + std::string(to_string(device)) + "/level" + std::to_string(level);
      benchmark::RegisterBenchmark(name.c_str(), solve_level, device, &problems)->Unit(benchmark::kMillisecond);
    }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
