#include "facecap/refine/vertex_sampler.hpp"

#if FACECAP_HAVE_CUDA
#include "facecap/refine/cuda/cuda_vertex_sampler.hpp"
#endif

namespace facecap {

namespace {

class CpuVertexSampler final : public VertexSampler {
 public:
  VertexSamples sample(const cv::Mat& image, const Positions& points, const Positions& normals,
                       const Positions& occluder_points, const std::vector<Triangle>& occluder_triangles,
                       const PinholeCamera& camera, RasterBuffers& cpu_buffers) override {
    return sample_vertices(image, points, normals, occluder_points, occluder_triangles, camera, cpu_buffers);
  }
};

}  // namespace

std::unique_ptr<VertexSampler> make_vertex_sampler(ComputeDevice device) {
  if (device == ComputeDevice::cpu) return std::make_unique<CpuVertexSampler>();
  require_cuda();
#if FACECAP_HAVE_CUDA
  return std::make_unique<CudaVertexSampler>();
#else
  return nullptr;  // not reached: require_cuda throws in a build without CUDA
#endif
}

}  // namespace facecap
