#include "facecap/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
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
