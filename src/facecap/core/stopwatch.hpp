#pragma once
// Milliseconds since a time point: the per-stage timings of the jobs and benchmarks.
#include <chrono>

namespace facecap {

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace facecap
