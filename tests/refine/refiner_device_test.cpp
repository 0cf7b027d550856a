// The refiner end to end on each device: the same frames refined with the
// displacement solve on the CPU and on the GPU give the same surface. Needs no
// face model: a rippled dome rendered by the project's rasteriser.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "cuda_test_support.hpp"
#include "facecap/refine/refiner.hpp"
#include "facecap/refine/vertex_sampler.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

namespace {

constexpr int kWidth = 640, kHeight = 480;

// A dome of n x n quads, 0.4 cm apart, 40 cm in front of the camera; with
// `detail` the grid is 4 times finer and rippled (what the camera sees).
struct Dome {
  std::vector<Polygon> polygons;
  std::vector<Triangle> triangles;
  Positions points;

  Dome(int n, bool detail) {
    const int m = detail ? 4 * n : n;
    const float step = 0.4f * float(n) / float(m);
    points.resize(3, (m + 1) * (m + 1));
    for (int y = 0; y <= m; ++y)
      for (int x = 0; x <= m; ++x) {
        const float px = step * (float(x) - m / 2.0f), py = step * (float(y) - m / 2.0f);
        float z = 40.0f + 0.04f * (px * px + py * py);
        if (detail) z += 0.03f * std::sin(3.0f * px) * std::cos(2.0f * py);
        points.col(y * (m + 1) + x) = Vec3f(px, py, z);
      }
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x) {
        const int a = y * (m + 1) + x;
        Polygon q;
        q.v = {a, a + m + 1, a + m + 2, a + 1};
        polygons.push_back(q);
        triangles.push_back({a, a + m + 1, a + m + 2});
        triangles.push_back({a, a + m + 2, a + 1});
      }
  }
};

Positions vertex_normals(const std::vector<Triangle>& triangles, const Positions& p) {
  Positions n = Positions::Zero(3, p.cols());
  for (const Triangle& t : triangles) {
    const Vec3f f = (Vec3f(p.col(t[1])) - Vec3f(p.col(t[0]))).cross(Vec3f(p.col(t[2])) - Vec3f(p.col(t[0])));
    for (int k = 0; k < 3; ++k) n.col(t[k]) += f;
  }
  for (Eigen::Index i = 0; i < n.cols(); ++i) n.col(i).normalize();
  return n;
}

cv::Mat render(const Dome& detailed, const PinholeCamera& camera) {
  ShCoeffs lighting = ShCoeffs::Zero();
  lighting << 0.7, 0.25, 0.3, 0.5, 0.05, 0.0, 0.0, 0.04, 0.02;
  RasterBuffers buffers;
  buffers.resize(kWidth, kHeight);
  rasterize(detailed.points, detailed.triangles, camera, buffers);
  cv::Mat canvas(kHeight, kWidth, CV_32FC3, cv::Scalar(0.1, 0.1, 0.1));
  const Positions albedo = Positions::Constant(3, detailed.points.cols(), 0.6f);
  shade_lambertian(buffers, detailed.triangles, albedo, vertex_normals(detailed.triangles, detailed.points), lighting,
                   canvas);
  cv::Mat image;
  canvas.convertTo(image, CV_8UC3, 255.0);
  return image;
}

}  // namespace

TEST(RefinerOnEachDevice, CudaRefinesTheSameSurfaceAsTheCpu) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const Dome coarse(24, false), detailed(24, true);
  const PinholeCamera camera = PinholeCamera::centered(900, kWidth, kHeight);
  const cv::Mat image = render(detailed, camera);
  RefineOptions options;
  options.albedo.frames = 2;
  options.device = ComputeDevice::cpu;
  Refiner on_cpu(coarse.polygons, static_cast<int>(coarse.points.cols()), options);
  options.device = ComputeDevice::cuda;
  Refiner on_gpu(coarse.polygons, static_cast<int>(coarse.points.cols()), options);
  for (int frame = 0; frame < 4; ++frame) {
    const Refinement a = on_cpu.refine(image, coarse.points, camera);
    const Refinement b = on_gpu.refine(image, coarse.points, camera);
    ASSERT_EQ(a.levels, b.levels);
    ASSERT_GE(a.levels, 2);
    ASSERT_EQ(a.positions.cols(), b.positions.cols());
    // Detail was found (the refined surface left the base) and both agree to 1 um.
    const Positions base = on_cpu.hierarchy().prolong_from_coarse(coarse.points, a.levels - 1);
    EXPECT_GT((a.positions - base).colwise().norm().maxCoeff(), 5e-3f) << "frame " << frame;
    EXPECT_LT((a.positions - b.positions).cwiseAbs().maxCoeff(), 1e-4f) << "frame " << frame;
    EXPECT_LT((a.lighting - b.lighting).norm(), 1e-4 * a.lighting.norm()) << "frame " << frame;
    EXPECT_TRUE(b.positions.allFinite());
  }
}

namespace {

// The pipeline's split (RefineStage): frame t's finer levels solved on
// another thread while frame t + 1's lighting, albedo and coarsest level are
// solved give what refine() gives one frame after another, to the bit.
void expect_halves_on_two_threads_refine_alike(ComputeDevice device) {
  const Dome coarse(24, false), detailed(24, true);
  const PinholeCamera camera = PinholeCamera::centered(900, kWidth, kHeight);
  const cv::Mat image = render(detailed, camera);
  RefineOptions options;
  options.albedo.frames = 2;
  options.albedo.interval = 1;
  options.device = device;
  Refiner sequential(coarse.polygons, static_cast<int>(coarse.points.cols()), options);
  Refiner pipelined(coarse.polygons, static_cast<int>(coarse.points.cols()), options);
  // The head moves a little from frame to frame, so each frame's solve differs.
  constexpr int kFrames = 5;
  std::vector<Positions> frames;
  for (int f = 0; f < kFrames; ++f) frames.push_back(coarse.points.colwise() + Vec3f(0.02f * f, -0.01f * f, 0.0f));
  std::vector<Refinement> expected, got(kFrames);
  for (int f = 0; f < kFrames; ++f) expected.push_back(sequential.refine(image, frames[f], camera));
  PendingFrame pending = pipelined.begin_frame(image, frames[0], camera);
  for (int f = 0; f < kFrames; ++f) {
    std::thread finisher([&, f, p = std::move(pending)]() mutable { got[f] = pipelined.finish_frame(std::move(p)); });
    if (f + 1 < kFrames) pending = pipelined.begin_frame(image, frames[f + 1], camera);
    finisher.join();
  }
  for (int f = 0; f < kFrames; ++f) {
    ASSERT_EQ(expected[f].positions.cols(), got[f].positions.cols()) << "frame " << f;
    EXPECT_TRUE(expected[f].positions == got[f].positions) << "frame " << f;
    EXPECT_TRUE(expected[f].normals == got[f].normals) << "frame " << f;
    EXPECT_TRUE(expected[f].lighting == got[f].lighting) << "frame " << f;
    EXPECT_TRUE(expected[f].albedo == got[f].albedo) << "frame " << f;
    EXPECT_EQ(expected[f].visible, got[f].visible) << "frame " << f;
    EXPECT_EQ(expected[f].albedo_final, got[f].albedo_final) << "frame " << f;
  }
  EXPECT_FALSE(got[0].albedo_final);
  EXPECT_TRUE(got[kFrames - 1].albedo_final);
}

}  // namespace

TEST(RefinerHalves, OnTwoThreadsTheyRefineAsRefineDoes) {
  expect_halves_on_two_threads_refine_alike(ComputeDevice::cpu);
}

TEST(RefinerHalves, OnTwoThreadsTheyRefineAsRefineDoesOnTheGpu) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  expect_halves_on_two_threads_refine_alike(ComputeDevice::cuda);
}

// The vertex sampling on each device: the detailed dome's vertices tested
// against the coarse dome's depth (as the refiner's finer levels are) and
// coloured from its render, at full and at half resolution.
TEST(VertexSamplerOnEachDevice, CudaSamplesWhatTheCpuSamples) {
  FACECAP_REQUIRE_CUDA_DEVICE();
  const Dome coarse(24, false), detailed(24, true);
  const PinholeCamera camera = PinholeCamera::centered(900, kWidth, kHeight);
  const cv::Mat image = render(detailed, camera);
  const Positions normals = vertex_normals(detailed.triangles, detailed.points);
  const auto cpu = make_vertex_sampler(ComputeDevice::cpu);
  const auto gpu = make_vertex_sampler(ComputeDevice::cuda);
  for (const int factor : {1, 2}) {
    cv::Mat scaled = image;
    if (factor > 1) scaled = image_pyramid(image, 2)[1];
    const PinholeCamera c = camera.resized(1.0 / factor);
    RasterBuffers buffers;
    const VertexSamples a = cpu->sample(scaled, detailed.points, normals, coarse.points, coarse.triangles, c, buffers);
    const VertexSamples b = gpu->sample(scaled, detailed.points, normals, coarse.points, coarse.triangles, c, buffers);
    ASSERT_EQ(a.visible.size(), b.visible.size());
    EXPECT_GT(a.visible_count, int(a.visible.size()) / 2);
    int differ = 0;
    float colour_diff = 0;
    for (size_t i = 0; i < a.visible.size(); ++i) {
      differ += a.visible[i] != b.visible[i];
      if (a.visible[i] && b.visible[i])
        colour_diff = std::max(colour_diff, (a.colour.col(i) - b.colour.col(i)).cwiseAbs().maxCoeff());
    }
    // The same arithmetic in the same order: the same vertices seen, the same colours.
    EXPECT_EQ(differ, 0) << "factor " << factor;
    EXPECT_LE(colour_diff, 1e-6f) << "factor " << factor;
    EXPECT_EQ(a.visible_count, b.visible_count);
  }
}

}  // namespace facecap
