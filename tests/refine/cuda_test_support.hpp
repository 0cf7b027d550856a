#pragma once
// The CPU/CUDA comparisons need a GPU; CI has none, so there they skip with a
// message (the CPU tests and a build of the CUDA code still run).
#include <gtest/gtest.h>

#include "facecap/refine/compute_device.hpp"

#define FACECAP_REQUIRE_CUDA_DEVICE()                                                                  \
  if (!::facecap::cuda_device_available()) {                                                           \
    GTEST_SKIP() << (::facecap::cuda_built()                                                           \
                         ? "no CUDA device here: the CPU/CUDA comparison runs on a machine with a GPU" \
                         : "this build has no CUDA backend (nvcc not found or -DFACECAP_CUDA=OFF)");   \
  }
