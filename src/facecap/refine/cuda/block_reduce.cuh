#pragma once
// Block-level sums for the kernels' reductions. Every thread of the block must
// call them (they synchronise the block).
#include <cuda_runtime.h>

namespace facecap::cuda {

constexpr int kBlockThreads = 256;  // the displacement kernels' block size

// The sum over the warp's 32 lanes, in lane 0.
__device__ inline double warp_sum(double value) {
  for (int offset = 16; offset > 0; offset /= 2) value += __shfl_down_sync(0xffffffffu, value, offset);
  return value;
}

// The sum over the block's Threads threads, in warp 0's lane 0 (other threads: undefined).
template <int Threads>
__device__ inline double block_sum_in_first_lane(double value) {
  static_assert(Threads % 32 == 0 && Threads <= 1024, "whole warps, at most 1024 threads");
  __shared__ double partial[Threads / 32];
  value = warp_sum(value);
  const int lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  if (lane == 0) partial[warp] = value;
  __syncthreads();
  if (warp == 0) value = warp_sum(lane < Threads / 32 ? partial[lane] : 0.0);
  return value;
}

// Adds the block's sum into one double in global memory with a single atomic.
__device__ inline void block_add(double value, double* out) {
  value = block_sum_in_first_lane<kBlockThreads>(value);
  if (threadIdx.x == 0 && value != 0.0) atomicAdd(out, value);
}

// The block's sum, returned to every thread. Consecutive calls may follow
// each other directly.
template <int Threads>
__device__ inline double block_sum(double value) {
  __shared__ double total;
  value = block_sum_in_first_lane<Threads>(value);
  if (threadIdx.x == 0) total = value;
  __syncthreads();
  return total;
}

}  // namespace facecap::cuda
