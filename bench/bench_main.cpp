// The benchmark programs' main: Google Benchmark's, after the allocator
// tuning that facecap's own main does, so that a stage is timed with the
// memory behaviour it has in the tool.
#include <benchmark/benchmark.h>

#include "facecap/core/allocator_tuning.hpp"

int main(int argc, char** argv) {
  facecap::keep_large_allocations_resident();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
