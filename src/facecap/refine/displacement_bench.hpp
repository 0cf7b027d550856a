#pragma once
// `facecap bench displacement DIR`: the displacement solve alone on saved
// problems (`eval refine --video V --save-problems DIR`), timed on each
// device and, with both, the CUDA results compared with the CPU reference.
#include <filesystem>
#include <vector>

#include "facecap/refine/compute_device.hpp"
#include "facecap/refine/displacement_solver.hpp"

namespace facecap {

struct DisplacementBenchOptions {
  std::vector<ComputeDevice> devices;  // the first is the reference when there are two
  int repeats = 5;                     // timed solves per problem (the median is kept)
  DisplacementOptions solver;
};

struct DeviceTiming {
  ComputeDevice device = ComputeDevice::cpu;
  std::vector<double> level_ms;  // per level: the mean over frames of each problem's median solve
  double frame_ms = 0;           // all levels of a frame
  double max_frame_ms = 0;       // the slowest frame
};

// The second device's results against the first's, over all problems.
struct DeviceAgreement {
  double max_abs_diff_um = 0;    // largest |d - d_ref| in micrometres
  double max_rel_diff = 0;       // largest |d - d_ref| over the problem's largest |d_ref|
  double max_cost_rel_diff = 0;  // |E - E_ref| / E_ref(initial)
  int same_steps = 0;            // problems solved in the same number of Gauss-Newton steps

  // The CUDA solve agrees with the CPU reference when no displacement differs
  // by more than this share of the problem's largest (float sums in another
  // order, FMA contraction on the GPU), and the energies by a part in 10^4.
  static constexpr double kRelDiff = 1e-2;
  static constexpr double kCostRelDiff = 1e-4;
  bool within_tolerance() const { return max_rel_diff <= kRelDiff && max_cost_rel_diff <= kCostRelDiff; }
};

// The agreement of one problem's two solves (d in centimetres).
DeviceAgreement compare_solves(const Eigen::VectorXf& d_ref, const DisplacementReport& ref, const Eigen::VectorXf& d,
                               const DisplacementReport& report);
// The worst of both.
DeviceAgreement worst(const DeviceAgreement& a, const DeviceAgreement& b);

struct DisplacementBenchResult {
  int problems = 0, frames = 0, levels = 0;
  std::vector<int> level_vertices;  // the largest count of free vertices seen per level
  std::vector<DeviceTiming> timings;
  bool compared = false;
  DeviceAgreement agreement;
};

// Throws facecap::Error when DIR holds no problem file or one is unreadable.
DisplacementBenchResult bench_displacement(const std::filesystem::path& dir, const DisplacementBenchOptions& options);

}  // namespace facecap
