#pragma once
// Data-parallel loop over an index range on the machine's cores.
#include <functional>
#include <vector>

namespace facecap {

// Number of threads parallel_for uses: FACECAP_THREADS when set to a positive
// number, else the hardware concurrency (at least 1).
int worker_count();

// The CPU time (ms) the pool's worker threads have spent so far, on every
// caller's loops together; 0 before the first loop that used them.
double pool_cpu_ms();

// Calls body(begin, end) on disjoint chunks that cover [0, n), in parallel.
// Small ranges (n < min_chunk) run on the calling thread.
void parallel_for(int n, const std::function<void(int, int)>& body, int min_chunk = 256);

// While one lives, parallel_for on its thread runs every loop on that
// thread alone. For a pipeline stage that runs beside a busier one on few
// cores: the pool's workers are then the busier stage's, and no core waits
// on a loop's last chunk.
class SerialScope {
 public:
  SerialScope();
  ~SerialScope();
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;

 private:
  bool was_serial_;
};

// Sum over [0, n) of block(begin, end), which returns its range's partial sum
// (a double, an Eigen array: anything with += and a zero): the range is cut
// into fixed blocks of `block_size` that run in parallel, and their sums are
// added in order, so the result does not depend on the number of threads.
template <typename T, typename Block>
T parallel_sum(int n, const Block& block, int block_size, const T& zero) {
  if (n <= 0) return zero;
  block_size = block_size > 0 ? block_size : 1;
  const int blocks = (n + block_size - 1) / block_size;
  std::vector<T> partial(blocks, zero);
  parallel_for(
      blocks,
      [&](int b, int e) {
        for (int k = b; k < e; ++k) {
          const int end = n - k * block_size < block_size ? n : (k + 1) * block_size;
          partial[k] = block(k * block_size, end);
        }
      },
      1);
  T sum = zero;
  for (const T& p : partial) sum += p;
  return sum;
}

}  // namespace facecap
