#include "facecap/core/cpu_time.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// Some milliseconds of arithmetic the compiler cannot drop.
double busy_work(int iterations) {
  volatile double x = 1.0;
  for (int i = 0; i < iterations; ++i) x = std::sqrt(x + double(i));
  return x;
}

}  // namespace

TEST(CpuTime, AThreadsCpuTimeGrowsWithItsWorkAndNotWhileItSleeps) {
  const double start = thread_cpu_ms();
  busy_work(30'000'000);
  const double worked = thread_cpu_ms();
  EXPECT_GT(worked - start, 5.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_LT(thread_cpu_ms() - worked, 20.0);  // waking up costs little
}

TEST(CpuTime, ThePoolsWorkersCountTheirShareOfALoop) {
  const double before = pool_cpu_ms();
  parallel_for(
      64, [](int b, int e) { busy_work(1'000'000 * (e - b)); }, 1);
  const double after = pool_cpu_ms();
  EXPECT_GE(after, before);
  if (worker_count() > 1) {
    EXPECT_GT(after, before);  // 64 chunks of a few ms: the workers took some
  }
}

}  // namespace facecap
