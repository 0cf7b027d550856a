// Output-writer benchmarks: one `track --refine --meshes` frame, the finest
// level of address_720p_a's hierarchy (33k vertices, 66k triangles, UVs), as
// an OBJ and as a PLY (with normals and colours too).
#include <benchmark/benchmark.h>

#include <random>

#include "facecap/core/temp_dir.hpp"
#include "facecap/io/mesh_writer.hpp"
#include "facecap/io/ply_writer.hpp"

namespace facecap {

namespace {

// A random stand-in for a refined frame: what the writers do does not
// depend on the values.
struct RefinedFrame {
  static constexpr int kVertices = 33063, kTriangles = 65600;
  Positions positions{3, kVertices}, normals{3, kVertices}, colours{3, kVertices};
  std::vector<Vec2f> uvs = std::vector<Vec2f>(kVertices);
  std::vector<Polygon> polygons = std::vector<Polygon>(kTriangles);

  RefinedFrame() {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> coordinate(-12.0f, 12.0f), unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> vertex(0, kVertices - 1);
    for (int i = 0; i < kVertices; ++i) {
      positions.col(i) = Vec3f(coordinate(rng), coordinate(rng), coordinate(rng));
      normals.col(i) = Vec3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
      colours.col(i) = Vec3f(unit(rng), unit(rng), unit(rng));
      uvs[size_t(i)] = Vec2f(unit(rng), unit(rng));
    }
    for (Polygon& p : polygons)
      for (int k = 0; k < 3; ++k) p.v[k] = p.uv[k] = vertex(rng);
  }
};

void BM_WriteObjRefinedFrame(benchmark::State& state) {
  const RefinedFrame f;
  TempDir dir;
  for (auto _ : state)
    write_obj(dir.path() / "frame.obj",
              {.positions = &f.positions, .polygons = &f.polygons, .uvs = &f.uvs, .comment = "benchmark"});
}
BENCHMARK(BM_WriteObjRefinedFrame)->Unit(benchmark::kMillisecond);

void BM_WritePlyRefinedFrame(benchmark::State& state) {
  const RefinedFrame f;
  TempDir dir;
  for (auto _ : state)
    write_ply(dir.path() / "frame.ply", {.positions = &f.positions,
                                         .polygons = &f.polygons,
                                         .normals = &f.normals,
                                         .colours = &f.colours,
                                         .uvs = &f.uvs,
                                         .comment = "benchmark"});
}
BENCHMARK(BM_WritePlyRefinedFrame)->Unit(benchmark::kMillisecond);

}  // namespace

}  // namespace facecap
