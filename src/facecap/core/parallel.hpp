#pragma once
// Data-parallel loop over an index range on the machine's cores.
#include <functional>

namespace facecap {

// Number of threads parallel_for uses: FACECAP_THREADS when set to a positive
// number, else the hardware concurrency (at least 1).
int worker_count();

// Calls body(begin, end) on disjoint chunks that cover [0, n), in parallel.
// Small ranges (n < min_chunk) run on the calling thread.
void parallel_for(int n, const std::function<void(int, int)>& body, int min_chunk = 256);

// Sum over [0, n) of block(begin, end), which returns its range's partial sum:
// the range is cut into fixed blocks of `block_size` that run in parallel, and
// their sums are added in order, so the result does not depend on the number
// of threads.
double parallel_sum(int n, const std::function<double(int, int)>& block, int block_size = 4096);

}  // namespace facecap
