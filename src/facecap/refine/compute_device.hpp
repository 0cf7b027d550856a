#pragma once
// Where the refinement's displacement solve runs: the CPU reference or the
// CUDA backend (refine/cuda), which is built when nvcc is found
// (-DFACECAP_CUDA=OFF builds without it).
#include <optional>
#include <string_view>

namespace facecap {

enum class ComputeDevice { cpu, cuda };

// Whether this build has the CUDA backend.
bool cuda_built();
// Whether the CUDA backend is built and a CUDA device answers.
bool cuda_device_available();
// Throws std::runtime_error saying why CUDA cannot be used here (this build
// has no CUDA backend, or no CUDA device answers); returns when it can.
void require_cuda();
// CUDA when a device answers, else the CPU.
ComputeDevice default_compute_device();

std::string_view to_string(ComputeDevice device);
// "cpu" or "cuda"; nothing for any other name.
std::optional<ComputeDevice> parse_compute_device(std::string_view name);

}  // namespace facecap
