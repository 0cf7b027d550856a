#include "facecap/refine/displacement_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/refine/displacement_backend.hpp"
#include "facecap/refine/displacement_problem_io.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Outcome {
  Eigen::VectorXf d;
  DisplacementReport report;
};

}  // namespace

DeviceAgreement compare_solves(const Eigen::VectorXf& d_ref, const DisplacementReport& ref, const Eigen::VectorXf& d,
                               const DisplacementReport& report) {
  DeviceAgreement a;
  if (d.size() != d_ref.size() || !d.allFinite()) {
    a.max_rel_diff = a.max_cost_rel_diff = a.max_abs_diff_um = std::numeric_limits<double>::infinity();
    return a;
  }
  const double diff = d.size() ? (d - d_ref).cwiseAbs().maxCoeff() : 0.0;
  const double largest = d_ref.size() ? d_ref.cwiseAbs().maxCoeff() : 0.0;
  a.max_abs_diff_um = diff * 1e4;
  a.max_rel_diff = largest > 0 ? diff / largest : (diff > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  a.max_cost_rel_diff = ref.initial_cost > 0 ? std::abs(report.final_cost - ref.final_cost) / ref.initial_cost : 0.0;
  a.same_steps = report.steps == ref.steps ? 1 : 0;
  return a;
}

DeviceAgreement worst(const DeviceAgreement& a, const DeviceAgreement& b) {
  DeviceAgreement w;
  w.max_abs_diff_um = std::max(a.max_abs_diff_um, b.max_abs_diff_um);
  w.max_rel_diff = std::max(a.max_rel_diff, b.max_rel_diff);
  w.max_cost_rel_diff = std::max(a.max_cost_rel_diff, b.max_cost_rel_diff);
  w.same_steps = a.same_steps + b.same_steps;
  return w;
}

DisplacementBenchResult bench_displacement(const fs::path& dir, const DisplacementBenchOptions& options) {
  if (options.devices.empty() || options.repeats < 1) throw Error("bench displacement: nothing to run");
  const std::vector<std::unique_ptr<SavedDisplacementProblem>> problems = load_displacement_problems(dir);

  DisplacementBenchResult result;
  result.problems = static_cast<int>(problems.size());
  std::map<int, int> frames;
  for (const auto& p : problems) {
    result.levels = std::max(result.levels, p->level_index + 1);
    frames[p->frame] = 1;
  }
  result.frames = static_cast<int>(frames.size());
  result.level_vertices.assign(result.levels, 0);
  for (const auto& p : problems) {
    const int active = p->problem.active.empty()
                           ? p->level.num_vertices
                           : static_cast<int>(std::count(p->problem.active.begin(), p->problem.active.end(), true));
    result.level_vertices[p->level_index] = std::max(result.level_vertices[p->level_index], active);
  }

  std::vector<std::vector<Outcome>> outcomes;
  for (const ComputeDevice device : options.devices) {
    const std::unique_ptr<DisplacementBackend> backend = make_displacement_backend(device);
    {  // warm-up: first allocations, the level's upload, the GPU's clocks
      Eigen::VectorXf d = problems.front()->start;
      backend->solve(problems.front()->problem, d, options.solver);
    }
    DeviceTiming timing;
    timing.device = device;
    timing.level_ms.assign(result.levels, 0.0);
    std::vector<int> level_count(result.levels, 0);
    std::map<int, double> frame_ms;
    std::vector<Outcome> out;
    for (const auto& p : problems) {
      std::vector<double> ms;
      Outcome o;
      for (int r = 0; r < options.repeats; ++r) {
        o.d = p->start;
        const auto t0 = std::chrono::steady_clock::now();
        o.report = backend->solve(p->problem, o.d, options.solver);
        ms.push_back(ms_since(t0));
      }
      const double m = median(ms);
      timing.level_ms[p->level_index] += m;
      ++level_count[p->level_index];
      frame_ms[p->frame] += m;
      out.push_back(std::move(o));
    }
    for (int l = 0; l < result.levels; ++l) timing.level_ms[l] /= std::max(1, level_count[l]);
    for (const auto& [frame, ms] : frame_ms) {
      timing.frame_ms += ms / double(frame_ms.size());
      timing.max_frame_ms = std::max(timing.max_frame_ms, ms);
    }
    result.timings.push_back(timing);
    outcomes.push_back(std::move(out));
  }

  if (outcomes.size() >= 2) {
    result.compared = true;
    for (size_t i = 0; i < problems.size(); ++i) {
      const Outcome& ref = outcomes[0][i];
      const Outcome& other = outcomes[1][i];
      result.agreement = worst(result.agreement, compare_solves(ref.d, ref.report, other.d, other.report));
    }
  }
  return result;
}

}  // namespace facecap
