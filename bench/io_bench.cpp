// Output-writer benchmarks: one `track --refine --meshes` frame, the finest
// level of address_720p_a's hierarchy (33k vertices, 66k triangles, UVs).
#include <benchmark/benchmark.h>

#include <random>

#include "facecap/core/temp_dir.hpp"
#include "facecap/io/mesh_writer.hpp"

namespace facecap {

namespace {

void BM_WriteObjRefinedFrame(benchmark::State& state) {
  constexpr int kVertices = 33063, kTriangles = 65600;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> coordinate(-12.0f, 12.0f), unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> vertex(0, kVertices - 1);
  Positions positions(3, kVertices);
  std::vector<Vec2f> uvs(kVertices);
  for (int i = 0; i < kVertices; ++i) {
    positions.col(i) = Vec3f(coordinate(rng), coordinate(rng), coordinate(rng));
    uvs[size_t(i)] = Vec2f(unit(rng), unit(rng));
  }
  std::vector<Polygon> polygons(kTriangles);
  for (Polygon& p : polygons)
    for (int k = 0; k < 3; ++k) p.v[k] = p.uv[k] = vertex(rng);
  TempDir dir;
  for (auto _ : state) write_obj(dir.path() / "frame.obj", {&positions, &polygons, &uvs, "benchmark"});
}
BENCHMARK(BM_WriteObjRefinedFrame)->Unit(benchmark::kMillisecond);

}  // namespace

}  // namespace facecap
