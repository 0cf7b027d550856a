#pragma once
// sample_vertices on an NVIDIA GPU (vertex_sampling_kernels.cuh): the frame's
// image and the meshes go up, the visibility and colours come back. Built
// only with FACECAP_CUDA; plain C++ interface.
#include <memory>

#include "facecap/refine/vertex_sampler.hpp"

namespace facecap {

class CudaVertexSampler final : public VertexSampler {
 public:
  // Throws std::runtime_error when no CUDA device answers (require_cuda).
  CudaVertexSampler();
  ~CudaVertexSampler() override;

  VertexSamples sample(const cv::Mat& image, const Positions& points, const Positions& normals,
                       const Positions& occluder_points, const std::vector<Triangle>& occluder_triangles,
                       const PinholeCamera& camera, RasterBuffers& cpu_buffers) override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace facecap
