// The wrinkle prediction's coating transfer (§6.1.2) on a mesh the size of
// a 720p face's finest 4-8 level (about 33k vertices).
#include <benchmark/benchmark.h>

#include <cmath>

#include "facecap/swap/wrinkle_transfer.hpp"
#include "swap/square_grid.hpp"  // tests/: the grid the coating transfer's tests use

namespace facecap {
namespace {

constexpr int kCells = 181;  // (181 + 1)^2 = 33124 vertices

std::vector<Triangle> grid_triangles() { return test::square_grid(kCells); }

// A curved sheet 10 cm across; `furrows` adds fine ripples.
Positions sheet(float furrows) {
  Positions p(3, (kCells + 1) * (kCells + 1));
  for (int y = 0; y <= kCells; ++y) {
    for (int x = 0; x <= kCells; ++x) {
      const float u = float(x) / kCells - 0.5f, v = float(y) / kCells - 0.5f;
      p.col(y * (kCells + 1) + x) = Vec3f(10 * u, 10 * v, 2 * (u * u + v * v) + furrows * std::sin(60 * v));
    }
  }
  return p;
}

void BM_CoatingTransferFactorisation(benchmark::State& state) {
  const std::vector<Triangle> triangles = grid_triangles();
  for (auto _ : state) {
    CoatingTransfer t(triangles, (kCells + 1) * (kCells + 1));
    benchmark::DoNotOptimize(t);
  }
}
BENCHMARK(BM_CoatingTransferFactorisation)->Unit(benchmark::kMillisecond);

void BM_CoatingTransferSolve(benchmark::State& state) {
  const CoatingTransfer t(grid_triangles(), (kCells + 1) * (kCells + 1));
  const Positions base = sheet(0.0f);
  const Positions coating = t.coating(sheet(0.01f), base);
  for (auto _ : state) benchmark::DoNotOptimize(t.solve(base, coating));
}
BENCHMARK(BM_CoatingTransferSolve)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace facecap
