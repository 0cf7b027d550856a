// Face-model benchmarks: loading through the binary cache, and evaluating
// neutral + B_id a + B_exp b for the face region.
#include <benchmark/benchmark.h>

#include "facecap/core/paths.hpp"
#include "facecap/model/model_cache.hpp"

namespace facecap {

namespace {

const FaceModel& model() {
  static const FaceModel m = load_face_model(default_model_dir());
  return m;
}

void BM_LoadModelFromCache(benchmark::State& state) {
  load_face_model(default_model_dir());  // make sure the cache exists
  for (auto _ : state) {
    ModelLoadReport report;
    benchmark::DoNotOptimize(load_face_model(default_model_dir(), &report));
    if (!report.from_cache) state.SkipWithError("cache was not used");
  }
}
BENCHMARK(BM_LoadModelFromCache)->Unit(benchmark::kMillisecond);

// Full evaluation: 50 identity modes and 53 expressions for the 9,409 face vertices.
void BM_EvaluateFaceRegion(benchmark::State& state) {
  const Eigen::VectorXf a = Eigen::VectorXf::Random(50);
  const Eigen::VectorXf b = Eigen::VectorXf::Random(53).cwiseAbs();
  for (auto _ : state) benchmark::DoNotOptimize(model().evaluate(a, b, regions::kFace));
}
BENCHMARK(BM_EvaluateFaceRegion)->Unit(benchmark::kMicrosecond);

// Per-frame evaluation during tracking: identity fixed, expressions only.
void BM_EvaluateFaceExpressions(benchmark::State& state) {
  const Eigen::VectorXf b = Eigen::VectorXf::Random(53).cwiseAbs();
  const Eigen::Index rows = 3 * regions::kFace.num_vertices();
  const Eigen::MatrixXf basis = model().expression_basis.topRows(rows);
  const Eigen::VectorXf shape = model().identity_shape(Eigen::VectorXf::Random(50), regions::kFace);
  Eigen::VectorXf out(rows);
  for (auto _ : state) {
    out.noalias() = shape + basis * b;
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_EvaluateFaceExpressions)->Unit(benchmark::kMicrosecond);

}  // namespace

}  // namespace facecap
