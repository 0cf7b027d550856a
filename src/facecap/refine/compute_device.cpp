#include "facecap/refine/compute_device.hpp"

namespace facecap {

bool cuda_built() { return FACECAP_HAVE_CUDA != 0; }

#if !FACECAP_HAVE_CUDA
bool cuda_device_available() { return false; }  // the CUDA build defines it in refine/cuda
#endif

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
