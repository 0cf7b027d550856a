#pragma once
// Block-level sums for the kernels' reductions: each block adds its threads'
// values into one double in global memory with a single atomic. Every thread
// of the block must call it (it synchronises the block).
#include <cuda_runtime.h>

namespace facecap::cuda {

constexpr int kBlockThreads = 256;  // the kernels' block size

__device__ inline void block_add(double value, double* out) {
  __shared__ double partial[kBlockThreads / 32];
  for (int offset = 16; offset > 0; offset /= 2) value += __shfl_down_sync(0xffffffffu, value, offset);
  const int lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  if (lane == 0) partial[warp] = value;
  __syncthreads();
  if (warp == 0) {
    value = lane < kBlockThreads / 32 ? partial[lane] : 0.0;
    for (int offset = 16; offset > 0; offset /= 2) value += __shfl_down_sync(0xffffffffu, value, offset);
    if (lane == 0 && value != 0.0) atomicAdd(out, value);
  }
}

}  // namespace facecap::cuda
