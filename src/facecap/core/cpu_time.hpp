#pragma once
// CPU time, for the benchmarks' budgets: on few cores a stage's wall time
// (stopwatch.hpp) includes its waits for a core, its CPU time does not, and
// the CPU times of all the stages together say whether the cores are full.
#include <time.h>

namespace facecap {

// A CPU-time clock's reading in milliseconds (0 where it cannot be read).
double clock_ms(clockid_t clock);

// The calling thread's CPU time since it started, in milliseconds.
inline double thread_cpu_ms() { return clock_ms(CLOCK_THREAD_CPUTIME_ID); }

// The whole process's CPU time, all its threads, in milliseconds.
inline double process_cpu_ms() { return clock_ms(CLOCK_PROCESS_CPUTIME_ID); }

}  // namespace facecap
