// Output-writer benchmarks: one `track --refine --meshes` frame, the finest
// level of address_720p_a's hierarchy (33k vertices, 66k triangles, UVs), as
// an OBJ and as a PLY (with normals and colours too); and the 16-bit PNGs of
// `--detail-maps` (a 1024-texel map) and `--uv-pass` (a 1280x720 pass).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "facecap/core/temp_dir.hpp"
#include "facecap/io/mesh_writer.hpp"
#include "facecap/io/ply_writer.hpp"
#include "facecap/io/png16.hpp"

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

// A stand-in detail map: smooth relief about the midlevel with a little
// noise in its low bits, over the whole square (ICT's face region fills 95 %
// of it).
void BM_EncodeDetailMap1024(benchmark::State& state) {
  cv::Mat map(1024, 1024, CV_16UC1);
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> noise(-40, 40);
  for (int y = 0; y < map.rows; ++y)
    for (int x = 0; x < map.cols; ++x)
      map.at<uint16_t>(y, x) = uint16_t(32768 + 600 * std::sin(x * 0.05) * std::cos(y * 0.03) + noise(rng));
  for (auto _ : state) benchmark::DoNotOptimize(encode_png16(map));
}
BENCHMARK(BM_EncodeDetailMap1024)->Unit(benchmark::kMillisecond);

// A stand-in UV pass: a face-sized ellipse (450 x 620 px) of smooth UVs in a
// 1280x720 frame, empty elsewhere.
void BM_EncodeUvPass720p(benchmark::State& state) {
  cv::Mat pass(720, 1280, CV_16UC4, cv::Scalar::all(0));
  for (int y = 100; y < 720; ++y)
    for (int x = 415; x < 865; ++x) {
      const double ex = (x - 640) / 225.0, ey = (y - 410) / 310.0;
      if (ex * ex + ey * ey > 1) continue;
      pass.at<cv::Vec<uint16_t, 4>>(y, x) = {0, uint16_t(65535 * (0.5 - 0.45 * ey)),
                                             uint16_t(65535 * (0.5 + 0.45 * ex)), 65535};
    }
  for (auto _ : state) benchmark::DoNotOptimize(encode_png16(pass));
}
BENCHMARK(BM_EncodeUvPass720p)->Unit(benchmark::kMillisecond);

}  // namespace

}  // namespace facecap
