#pragma once
// A job's share of the cores, for a benchmark's budget (core/cpu_time.hpp):
// the encoder process's CPU time, and that of the pool's workers and of all
// of facecap's threads since the job (or the part of it timed) began.
#include "facecap/core/cpu_time.hpp"
#include "facecap/core/parallel.hpp"

namespace facecap {

struct JobCpu {
  double encoder_ms = 0;
  double pool_ms = 0;
  double process_ms = 0;  // all of facecap's threads (the encoder is another process)
};

// The pool's and the process's CPU time read at construction (or at
// restart()); taken() gives the job's share since then, with the encoder's.
class JobCpuClock {
 public:
  JobCpuClock() { restart(); }
  void restart() {
    pool_ = pool_cpu_ms();
    process_ = process_cpu_ms();
  }
  JobCpu taken(double encoder_ms) const { return {encoder_ms, pool_cpu_ms() - pool_, process_cpu_ms() - process_}; }

 private:
  double pool_ = 0, process_ = 0;
};

}  // namespace facecap
