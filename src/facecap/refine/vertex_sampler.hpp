#pragma once
// sample_vertices (vertex_samples.hpp) on a chosen device: the depth test
// against an occluding mesh and each vertex's colour. The CUDA sampler
// rasterises on the GPU and keeps its buffers and the occluder's triangles
// there from frame to frame.
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/refine/compute_device.hpp"
#include "facecap/refine/vertex_samples.hpp"

namespace facecap {

class VertexSampler {
 public:
  virtual ~VertexSampler() = default;
  // As sample_vertices with an occluder; `cpu_buffers` are the CPU's raster
  // buffers (the CUDA sampler does not touch them).
  virtual VertexSamples sample(const cv::Mat& image, const Positions& points, const Positions& normals,
                               const Positions& occluder_points, const std::vector<Triangle>& occluder_triangles,
                               const PinholeCamera& camera, RasterBuffers& cpu_buffers) = 0;
};

// Throws std::runtime_error for CUDA when this build has no CUDA backend or
// no CUDA device answers.
std::unique_ptr<VertexSampler> make_vertex_sampler(ComputeDevice device);

}  // namespace facecap
