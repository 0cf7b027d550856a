#include "facecap/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <numeric>
#include <thread>
#include <vector>

namespace facecap {

TEST(ParallelFor, CoversEveryIndexExactlyOnce) {
  std::vector<int> hits(100000, 0);
  parallel_for(static_cast<int>(hits.size()), [&](int b, int e) {
    for (int i = b; i < e; ++i) ++hits[i];
  });
  for (int h : hits) ASSERT_EQ(h, 1);
}

TEST(ParallelFor, NestedAndConcurrentCallsComplete) {
  std::atomic<long> sum{0};
  auto job = [&] {
    for (int rep = 0; rep < 50; ++rep) {
      parallel_for(
          64,
          [&](int b, int e) {
            for (int i = b; i < e; ++i) {
              parallel_for(
                  100, [&](int bb, int ee) { sum += ee - bb; }, 10);
            }
          },
          1);
    }
  };
  std::thread other(job);
  job();
  other.join();
  EXPECT_EQ(sum.load(), 2L * 50 * 64 * 100);
}

TEST(ParallelFor, EmptyRangeCallsNothing) {
  bool called = false;
  parallel_for(0, [&](int, int) { called = true; });
  EXPECT_FALSE(called);
}

// A stage beside a busier one keeps its loops to its own thread.
TEST(ParallelFor, ASerialScopeRunsTheLoopWholeOnItsOwnThread) {
  const auto calls_of = [](int n) {
    std::vector<std::pair<int, int>> ranges;
    std::vector<std::thread::id> threads;
    std::mutex m;
    parallel_for(
        n,
        [&](int b, int e) {
          const std::lock_guard lock(m);
          ranges.emplace_back(b, e);
          threads.push_back(std::this_thread::get_id());
        },
        1);
    return std::make_pair(ranges, threads);
  };
  {
    const SerialScope serial;
    { const SerialScope nested; }
    // Still serial after the nested scope ends.
    const auto [ranges, threads] = calls_of(1000);
    ASSERT_EQ(ranges.size(), 1u);
    EXPECT_EQ(ranges[0], std::make_pair(0, 1000));
    EXPECT_EQ(threads[0], std::this_thread::get_id());
  }
  // And shared again once the scope ends, where there are workers.
  const auto [ranges, threads] = calls_of(1000);
  if (worker_count() > 1) {
    EXPECT_GT(ranges.size(), 1u);
  }
  int covered = 0;
  for (const auto& [b, e] : ranges) covered += e - b;
  EXPECT_EQ(covered, 1000);
}

TEST(ParallelSum, CoversEveryIndexOnceAndAddsTheBlocks) {
  const int n = 100003;
  std::vector<int> calls(n, 0);
  const double sum = parallel_sum(
      n,
      [&](int b, int e) {
        double s = 0;
        for (int i = b; i < e; ++i) {
          ++calls[i];
          s += i;
        }
        return s;
      },
      1000, 0.0);
  EXPECT_EQ(sum, double(n) * (n - 1) / 2);
  for (int i = 0; i < n; ++i) ASSERT_EQ(calls[i], 1) << i;
  EXPECT_EQ(parallel_sum(
                0, [](int, int) { return 1.0; }, 1000, 0.0),
            0.0);
}

}  // namespace facecap
