// Shape-from-shading refinement benchmarks on a synthetic 1280x720 render
// with wrinkles: one frame's refinement once the albedo is fixed (lighting,
// the displacement solve at every level), as `facecap track --refine` runs it
// after its first frames. The frames alternate so that the warm start from
// the previous frame is a real one.
#include <benchmark/benchmark.h>

#include <random>

#include "facecap/core/paths.hpp"
#include "facecap/model/model_cache.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/synth/synth_renderer.hpp"

namespace facecap {

namespace {

struct Scene {
  FaceModel model = load_face_model(default_model_dir());
  SynthPerformance performance;
  std::vector<cv::Mat> images;
  std::vector<Positions> coarse;

  Scene() {
    SynthOptions o;
    o.frames = 8;
    o.width = 1280;
    o.height = 720;
    o.detail = true;
    performance = make_performance(model, o);
    const SynthRenderer renderer(model, performance);
    std::mt19937_64 rng(7);
    for (const SynthFrame& f : performance.frames) {
      images.push_back(renderer.render(f, rng));
      coarse.push_back(to_camera(model.evaluate(performance.identity, f.expression, regions::kFace), f.pose));
    }
  }
};

const Scene& scene() {
  static const Scene s;
  return s;
}

void BM_RefineFrame720p(benchmark::State& state) {
  const Scene& s = scene();
  RefineOptions options;
  options.albedo.frames = 1;  // fixed after the first frame: measure the per-frame work
  Refiner refiner = make_face_refiner(s.model, options);
  refiner.refine(s.images[0], s.coarse[0], s.performance.camera);
  size_t frame = 1;
  long frames = 0;
  double lighting_ms = 0;
  std::vector<double> level_ms;
  for (auto _ : state) {
    const Refinement r = refiner.refine(s.images[frame], s.coarse[frame], s.performance.camera);
    frame = frame + 1 < s.images.size() ? frame + 1 : 1;
    ++frames;
    lighting_ms += r.timings.lighting_ms;
    level_ms.resize(r.timings.level_ms.size());
    for (size_t l = 0; l < level_ms.size(); ++l) level_ms[l] += r.timings.level_ms[l];
  }
  const double n = double(std::max(1L, frames));
  state.counters["lighting_ms"] = lighting_ms / n;
  for (size_t l = 0; l < level_ms.size(); ++l) state.counters["level" + std::to_string(l) + "_ms"] = level_ms[l] / n;
}
BENCHMARK(BM_RefineFrame720p)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// One frame's lighting alone, as the edits refine their target (transform,
// swap: lighting_only_refinement), once the albedo is fixed.
void BM_LightingOnlyFrame720p(benchmark::State& state) {
  const Scene& s = scene();
  RefineOptions options = lighting_only_refinement();
  options.albedo.frames = 1;
  Refiner refiner = make_face_refiner(s.model, options);
  refiner.refine(s.images[0], s.coarse[0], s.performance.camera);
  size_t frame = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(refiner.refine(s.images[frame], s.coarse[frame], s.performance.camera));
    frame = frame + 1 < s.images.size() ? frame + 1 : 1;
  }
}
BENCHMARK(BM_LightingOnlyFrame720p)->Unit(benchmark::kMillisecond);

// Rasterising the finest level at 1280x720 (depth, triangle and barycentric
// buffers reused across frames). The displacement solve's depth test at the
// finest level rasterises the coarse mesh instead (the same surface):
// BM_RasterizeCoarseMesh720p.
void BM_RasterizeFinestLevel720p(benchmark::State& state) {
  const Scene& s = scene();
  Refiner refiner = make_face_refiner(s.model, RefineOptions{});
  refiner.refine(s.images[0], s.coarse[0], s.performance.camera);
  const MeshHierarchy& h = refiner.hierarchy();
  const int finest = h.num_levels() - 1;
  std::vector<Positions> frames;
  for (const Positions& c : s.coarse) {
    Positions p = c;
    for (int l = 1; l <= finest; ++l) p = h.prolong(p, l);
    frames.push_back(p);
  }
  RasterBuffers buffers;
  buffers.resize(s.images[0].cols, s.images[0].rows);
  size_t frame = 0;
  for (auto _ : state) {
    rasterize(frames[frame], h.level(finest).triangles, s.performance.camera, buffers);
    benchmark::DoNotOptimize(buffers.depth.data());
    frame = (frame + 1) % frames.size();
  }
  state.counters["triangles"] = double(h.level(finest).triangles.size());
}
BENCHMARK(BM_RasterizeFinestLevel720p)->Unit(benchmark::kMillisecond);

// The coarse mesh at 1280x720: the depth the finest level's vertices are
// tested against, every frame.
void BM_RasterizeCoarseMesh720p(benchmark::State& state) {
  const Scene& s = scene();
  Refiner refiner = make_face_refiner(s.model, RefineOptions{});
  refiner.refine(s.images[0], s.coarse[0], s.performance.camera);
  const std::vector<Triangle>& triangles = refiner.hierarchy().level(0).triangles;
  RasterBuffers buffers;
  buffers.resize(s.images[0].cols, s.images[0].rows);
  size_t frame = 0;
  for (auto _ : state) {
    rasterize(s.coarse[frame], triangles, s.performance.camera, buffers);
    benchmark::DoNotOptimize(buffers.depth.data());
    frame = (frame + 1) % s.coarse.size();
  }
  state.counters["triangles"] = double(triangles.size());
}
BENCHMARK(BM_RasterizeCoarseMesh720p)->Unit(benchmark::kMillisecond);

// The albedo phase of a video's first frames: lighting and albedo estimated
// jointly over 8 albedo frames (4 lighting/albedo rounds at each, 100 PCG
// iterations per solve), without the displacement solve.
void BM_AlbedoPhase(benchmark::State& state) {
  const Scene& s = scene();
  RefineOptions options;
  options.displacements = false;
  options.albedo.frames = static_cast<int>(s.images.size());
  options.albedo.interval = 1;
  double albedo_ms = 0;
  long phases = 0;
  for (auto _ : state) {
    Refiner refiner = make_face_refiner(s.model, options);
    for (size_t f = 0; f < s.images.size(); ++f)
      albedo_ms += refiner.refine(s.images[f], s.coarse[f], s.performance.camera).timings.albedo_ms;
    ++phases;
  }
  state.counters["albedo_ms"] = albedo_ms / double(std::max(1L, phases));
}
BENCHMARK(BM_AlbedoPhase)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

}  // namespace facecap
