#pragma once
// CPU time, for the benchmarks' budgets: on few cores a stage's wall time
// (stopwatch.hpp) includes its waits for a core, its CPU time does not, and
// the CPU times of all the stages together say whether the cores are full.
namespace facecap {

// The calling thread's CPU time since it started, in milliseconds.
double thread_cpu_ms();

}  // namespace facecap
