#pragma once
// An owning device allocation (cudaMalloc, never managed memory) that grows
// on demand and is reused across frames, and the error check every CUDA call
// goes through.
#include <cuda_runtime.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace facecap::cuda {

// Throws std::runtime_error naming `what` and CUDA's message when `status` is an error.
void check(cudaError_t status, const char* what);

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  ~DeviceBuffer() { cudaFree(data_); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), capacity_(std::exchange(o.capacity_, 0)) {}
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(capacity_, o.capacity_);
    return *this;
  }

  // At least n elements; the contents are lost when it grows.
  T* reserve(std::size_t n) {
    if (n > capacity_) {
      cudaFree(data_);
      data_ = nullptr;
      capacity_ = 0;
      check(cudaMalloc(reinterpret_cast<void**>(&data_), n * sizeof(T)), "cudaMalloc");
      capacity_ = n;
    }
    return data_;
  }
  // Copies n elements in on `stream` (asynchronous with respect to the host
  // only for pinned sources); returns the device pointer, null for n = 0.
  T* upload(const T* host, std::size_t n, cudaStream_t stream) {
    if (n == 0) return nullptr;
    reserve(n);
    check(cudaMemcpyAsync(data_, host, n * sizeof(T), cudaMemcpyHostToDevice, stream), "copy to the GPU");
    return data_;
  }
  T* upload(const std::vector<T>& host, cudaStream_t stream) { return upload(host.data(), host.size(), stream); }
  T* get() const { return data_; }

 private:
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

// Page-locked host memory: what a frame is packed into for one upload, and
// where results land.
template <typename T>
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  ~PinnedBuffer() { cudaFreeHost(data_); }
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;
  T* reserve(std::size_t n) {
    if (n > capacity_) {
      cudaFreeHost(data_);
      data_ = nullptr;
      capacity_ = 0;
      check(cudaMallocHost(reinterpret_cast<void**>(&data_), n * sizeof(T)), "cudaMallocHost");
      capacity_ = n;
    }
    return data_;
  }
  T* get() const { return data_; }

 private:
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

}  // namespace facecap::cuda
