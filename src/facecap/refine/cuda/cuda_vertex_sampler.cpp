#include "facecap/refine/cuda/cuda_vertex_sampler.hpp"

#include <cstring>
#include <stdexcept>

#include "facecap/core/error.hpp"
#include "facecap/refine/cuda/device_buffer.hpp"
#include "facecap/refine/cuda/vertex_sampling_kernels.cuh"

namespace facecap {

using cuda::check;
using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

struct CudaVertexSampler::State {
  cudaStream_t stream = nullptr;
  PinnedBuffer<unsigned char> staging, results;
  DeviceBuffer<unsigned char> upload, visible;
  DeviceBuffer<float> colour;
  DeviceBuffer<unsigned> depth;
  // The occluder's triangles: the refiner's skin triangles, the same vector
  // for its whole life, found again by address, size and end triangles (a
  // vector freed and another made in its place would differ in those).
  const Triangle* triangles_key = nullptr;
  std::size_t triangles_count = 0;
  Triangle triangles_first{}, triangles_last{};

  bool holds(const std::vector<Triangle>& t) const {
    return triangles_key == t.data() && triangles_count == t.size() &&
           (t.empty() || (triangles_first == t.front() && triangles_last == t.back()));
  }
  DeviceBuffer<int> triangles;

  State() { check(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate"); }
  ~State() { cudaStreamDestroy(stream); }
};

CudaVertexSampler::CudaVertexSampler() {
  require_cuda();
  state_ = std::make_unique<State>();
}

CudaVertexSampler::~CudaVertexSampler() = default;

VertexSamples CudaVertexSampler::sample(const cv::Mat& image, const Positions& points, const Positions& normals,
                                        const Positions& occluder_points,
                                        const std::vector<Triangle>& occluder_triangles, const PinholeCamera& camera,
                                        RasterBuffers&) {
  if (image.type() != CV_8UC3) throw Error("vertex sampling needs an 8-bit BGR image");
  State& s = *state_;
  const cudaStream_t stream = s.stream;
  const int n = static_cast<int>(points.cols()), m = static_cast<int>(occluder_points.cols());
  const int width = image.cols, height = image.rows;
  if (!s.holds(occluder_triangles)) {
    s.triangles.upload(occluder_triangles.empty() ? nullptr : occluder_triangles.front().data(),
                       3 * occluder_triangles.size(), stream);
    check(cudaStreamSynchronize(stream), "copy to the GPU");
    s.triangles_key = occluder_triangles.data();
    s.triangles_count = occluder_triangles.size();
    if (!occluder_triangles.empty()) {
      s.triangles_first = occluder_triangles.front();
      s.triangles_last = occluder_triangles.back();
    }
  }

  // The image and the meshes in one copy: floats first, then the pixels.
  const std::size_t floats = 3 * std::size_t(2 * n + m), row_bytes = 3 * std::size_t(width);
  const std::size_t bytes = floats * sizeof(float) + row_bytes * height;
  unsigned char* staged = s.staging.reserve(bytes);
  float* staged_floats = reinterpret_cast<float*>(staged);
  std::memcpy(staged_floats, points.data(), 3 * n * sizeof(float));
  std::memcpy(staged_floats + 3 * n, normals.data(), 3 * n * sizeof(float));
  std::memcpy(staged_floats + 6 * n, occluder_points.data(), 3 * m * sizeof(float));
  unsigned char* staged_pixels = staged + floats * sizeof(float);
  for (int y = 0; y < height; ++y) std::memcpy(staged_pixels + y * row_bytes, image.ptr(y), row_bytes);
  unsigned char* on_device = s.upload.reserve(bytes);
  check(cudaMemcpyAsync(on_device, staged, bytes, cudaMemcpyHostToDevice, stream), "copy to the GPU");
  const float* device_floats = reinterpret_cast<const float*>(on_device);

  cuda::CameraView c;
  c.focal = float(camera.focal);
  c.cx = float(camera.cx);
  c.cy = float(camera.cy);
  c.focal_d = camera.focal;
  unsigned* depth = s.depth.reserve(std::size_t(width) * height);
  cuda::launch_depth_raster(device_floats + 6 * n, m, s.triangles.get(), static_cast<int>(occluder_triangles.size()), c,
                            RasterOptions{}.near_z, depth, width, height, stream);
  cuda::ImageView view{on_device + floats * sizeof(float), width, height, static_cast<int>(row_bytes)};
  unsigned char* visible = s.visible.reserve(std::max(n, 1));
  float* colour = s.colour.reserve(3 * std::size_t(std::max(n, 1)));
  // The depth tolerance sample_vertices uses.
  cuda::launch_vertex_samples(device_floats, device_floats + 3 * n, n, c, depth, view, 0.1f, visible, colour, stream);
  check(cudaGetLastError(), "vertex sampling");

  // The samples out.
  unsigned char* back = s.results.reserve(n * (1 + 3 * sizeof(float)));
  check(cudaMemcpyAsync(back, colour, 3 * n * sizeof(float), cudaMemcpyDeviceToHost, stream), "copy from the GPU");
  check(cudaMemcpyAsync(back + 3 * n * sizeof(float), visible, n, cudaMemcpyDeviceToHost, stream), "copy from the GPU");
  check(cudaStreamSynchronize(stream), "vertex sampling");
  VertexSamples out;
  out.colour.resize(3, n);
  std::memcpy(out.colour.data(), back, 3 * n * sizeof(float));
  out.visible.resize(n);
  const unsigned char* seen = back + 3 * n * sizeof(float);
  for (int i = 0; i < n; ++i) {
    out.visible[i] = seen[i] != 0;
    out.visible_count += seen[i] != 0;
  }
  return out;
}

}  // namespace facecap
