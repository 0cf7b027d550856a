#include "facecap/refine/compute_device.hpp"

#include <stdexcept>

namespace facecap {

bool cuda_built() { return FACECAP_HAVE_CUDA != 0; }

#if !FACECAP_HAVE_CUDA
bool cuda_device_available() { return false; }  // the CUDA build defines it in refine/cuda
#endif

void require_cuda() {
  if (!cuda_built())
    throw std::runtime_error(
        "this facecap was built without CUDA (nvcc was not found, or -DFACECAP_CUDA=OFF): use --device cpu");
  if (!cuda_device_available()) throw std::runtime_error("no CUDA device is available: use --device cpu");
}

ComputeDevice default_compute_device() {
  static const ComputeDevice device = cuda_device_available() ? ComputeDevice::cuda : ComputeDevice::cpu;
  return device;
}

std::string_view to_string(ComputeDevice device) { return device == ComputeDevice::cuda ? "cuda" : "cpu"; }

std::optional<ComputeDevice> parse_compute_device(std::string_view name) {
  if (name == "cpu") return ComputeDevice::cpu;
  if (name == "cuda") return ComputeDevice::cuda;
  return std::nullopt;
}

}  // namespace facecap
