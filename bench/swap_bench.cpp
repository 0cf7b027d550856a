// The wrinkle prediction's coating transfer (§6.1.2) on a mesh the size of
// a 720p face's finest 4-8 level (about 33k vertices), the render's
// silhouette fade and the background warp on a window the size of a 720p
// swap's, the moving cover's flow on a face as wide as a 720p one, and a
// whole swap of a synthetic 720p frame and its preparation.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>
#include "facecap/render/outline_distance.hpp"

#include "facecap/compose/laplacian_blend.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/model/model_cache.hpp"
#include "facecap/swap/background_warp.hpp"
#include "facecap/swap/expression_ratio.hpp"
#include "facecap/swap/frame_preparation.hpp"
#include "facecap/swap/moving_cover.hpp"
#include "facecap/swap/silhouette_fade.hpp"
#include "facecap/swap/wrinkle_transfer.hpp"
#include "facecap/synth/synth_renderer.hpp"
#include "swap/square_grid.hpp"  // tests/: the grid the coating transfer's tests use
#include "swap/two_faces.hpp"    // tests/: FaceSwapper's synthetic source and target
#include "swap/unit_square.hpp"  // tests/: a unit square with UVs, the ratio's grid

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

// A 720p swap's window (420 x 560) with a face-sized ellipse drawn, two eye
// openings and a mouth in it, and a band of surface turned away (a nose's
// underside) inside.
constexpr int kWindowWidth = 420, kWindowHeight = 560;

RasterBuffers face_window() {
  RasterBuffers b;
  b.resize(kWindowWidth, kWindowHeight);
  const auto in_ellipse = [](int x, int y, float cx, float cy, float rx, float ry) {
    const float u = (x - cx) / rx, v = (y - cy) / ry;
    return u * u + v * v <= 1.0f;
  };
  for (int y = 0; y < b.height; ++y) {
    for (int x = 0; x < b.width; ++x) {
      const bool face = in_ellipse(x, y, 210, 280, 150, 200);
      const bool opening = in_ellipse(x, y, 150, 230, 25, 10) || in_ellipse(x, y, 270, 230, 25, 10) ||
                           in_ellipse(x, y, 210, 380, 45, 12);
      if (face && !opening) b.triangle[size_t(y) * b.width + x] = 0;
    }
  }
  return b;
}

void BM_OutlineDistance720p(benchmark::State& state) {
  const RasterBuffers b = face_window();
  for (auto _ : state) benchmark::DoNotOptimize(outline_distance(b));
}
BENCHMARK(BM_OutlineDistance720p)->Unit(benchmark::kMillisecond);

void BM_SoftenTurnedAway720p(benchmark::State& state) {
  const RasterBuffers b = face_window();
  const cv::Mat outline = outline_distance(b);
  cv::Mat turned(kWindowHeight, kWindowWidth, CV_32F, cv::Scalar(0));
  turned(cv::Rect(170, 300, 80, 20)).setTo(1.0f);  // the nose's underside
  const cv::Mat render(kWindowHeight, kWindowWidth, CV_32FC3, cv::Scalar(180, 140, 120));
  const SilhouetteFade fade{0.3f, 30.0f};
  for (auto _ : state) {
    cv::Mat r = render.clone();
    soften_turned_away(r, turned, outline, fade);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_SoftenTurnedAway720p)->Unit(benchmark::kMillisecond);

// The background warp of a 720p swap: 100 anchors (36 on a face-sized
// outline, 64 inside it) that the new face moves by up to 12 px, the
// window above, the frame 1280 x 720.
void BM_BackgroundWarp720p(benchmark::State& state) {
  cv::Mat frame(720, 1280, CV_8UC3);
  cv::RNG(3).fill(frame, cv::RNG::UNIFORM, 0, 255);
  const cv::Rect window(430, 80, kWindowWidth, kWindowHeight);
  const cv::Point2f centre(640, 360);
  std::vector<cv::Point2f> from, to;
  for (int k = 0; k < 100; ++k) {
    const float angle = 6.2831853f * float(k % 36) / 36, radius = k < 36 ? 1.0f : 0.2f + 0.7f * float(k - 36) / 64;
    const cv::Point2f p = centre + cv::Point2f(150 * radius * std::cos(angle + k), 200 * radius * std::sin(angle + k));
    from.push_back(p);
    to.push_back(centre + cv::Point2f(0.92f * (p.x - centre.x), p.y - centre.y + 4 * std::sin(0.05f * p.x)));
  }
  BackgroundWarp warp;
  cv::Mat out;
  for (auto _ : state) {
    warp.warp(frame, from, to, window, out);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_BackgroundWarp720p)->Unit(benchmark::kMillisecond);

// A flat face 25 cm square (a UV grid of 250 texels, as the ICT face's at
// 1 mm) 80 cm from a 1280x720 camera of focal 1000 px: 312 px across, its
// grain moving 3 px a frame while the model stays (the tracking's error,
// which the shared field takes out).
void BM_MovingCover720p(benchmark::State& state) {
  constexpr int kSide = 60;
  TriangleMesh skin;
  skin.num_vertices = (kSide + 1) * (kSide + 1);
  skin.triangles = test::square_grid(kSide);
  skin.triangle_uvs = skin.triangles;
  Positions points(3, skin.num_vertices);
  for (int y = 0; y <= kSide; ++y) {
    for (int x = 0; x <= kSide; ++x) {
      const float u = float(x) / kSide, v = float(y) / kSide;
      skin.uvs.emplace_back(u, v);
      points.col(y * (kSide + 1) + x) = Vec3f(25 * (u - 0.5f), -25 * (v - 0.5f), 80);
    }
  }
  const MillimetreGrid grid = millimetre_grid(skin, 250.0, 1.0);
  const PinholeCamera camera = PinholeCamera::centered(1000.0, 1280, 720);
  cv::Mat texture(720, 1400, CV_8U);
  cv::RNG(5).fill(texture, cv::RNG::UNIFORM, 60, 200);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::Mat frames[2];
  for (int k = 0; k < 2; ++k) cv::cvtColor(texture(cv::Rect(3 * k, 0, 1280, 720)), frames[k], cv::COLOR_GRAY2BGR);
  const cv::Mat seen(grid.map.size, grid.map.size, CV_32F, cv::Scalar(1));
  MovingCover mover(skin, grid);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(mover.update(frames[k], points, camera, seen));
    k = 1 - k;
  }
}
BENCHMARK(BM_MovingCover720p)->Unit(benchmark::kMillisecond);

// The expression ratio's gains on a grid the size of a face's (250 mm
// square at 1 mm a texel), every texel seen: a grainy reference, and a
// frame with the grain changed.
void BM_ExpressionRatioGains(benchmark::State& state) {
  ExpressionRatio ratio(test::unit_square(), 250.0);
  const auto grainy = [&](int seed) {
    FaceTexture t;
    t.albedo = cv::Mat(ratio.grid_size(), ratio.grid_size(), CV_32FC3);
    cv::RNG(seed).fill(t.albedo, cv::RNG::UNIFORM, 0.3, 0.7);
    t.weight = cv::Mat(t.albedo.size(), CV_32F, cv::Scalar(1));
    return t;
  };
  ratio.add_reference(grainy(1));
  const FaceTexture frame = grainy(2);
  for (auto _ : state) benchmark::DoNotOptimize(ratio.gains(frame));
}
BENCHMARK(BM_ExpressionRatioGains)->Unit(benchmark::kMillisecond);

// The swap's multi-band blend on a window the size of a 720p face's (410 x
// 570 px), the new face an ellipse in it.
void BM_LaplacianBlend720p(benchmark::State& state) {
  const cv::Size size(410, 570);
  cv::Mat base(size, CV_8UC3), layer(size, CV_8UC3), mask(size, CV_8U, cv::Scalar(0));
  cv::RNG(3).fill(base, cv::RNG::UNIFORM, 0, 255);
  cv::RNG(4).fill(layer, cv::RNG::UNIFORM, 0, 255);
  cv::ellipse(mask, cv::Point(205, 285), cv::Size(150, 210), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  const cv::Mat soft = feather_mask(mask, 0, 8.0);
  for (auto _ : state) benchmark::DoNotOptimize(laplacian_blend(base, layer, soft));
}
BENCHMARK(BM_LaplacianBlend720p)->Unit(benchmark::kMillisecond);

// One face swapped into renders of another at 1280x720, with the true
// parameters, after the appearance frames: the swap's thread's work for one
// frame (`bench swap`'s swap_ms_per_frame), and the preparation a stream
// makes of each frame beside it (preparation_ms_per_frame). The face is 216
// px from chin to brow, about as many pixels as `address_720p_a`'s (50-55k
// drawn), so that the texture is read at about the same level of detail.
struct SwapScene {
  static constexpr int kFrames = 8;
  FaceModel model = load_face_model(default_model_dir());
  test::TwoFaces faces;
  cv::Mat photo;
  std::vector<cv::Mat> frames;
  std::vector<Positions> points;  // each frame's face in camera space (a stream's tracked face)

  SwapScene() {
    SynthOptions o;
    o.frames = kFrames;
    o.width = 1280;
    o.height = 720;
    o.face_height = 0.3;
    faces = test::two_faces(model, o, 9);
    const SynthRenderer target(model, faces.target), source(model, faces.source);
    std::mt19937_64 rng(1);
    photo = source.render(faces.source.frames[0], rng);
    for (const SynthFrame& f : faces.target.frames) {
      frames.push_back(target.render(f, rng));
      points.push_back(test::face_points(model, faces.target, f));
    }
  }

  // The frame number of step `k` of an endless loop over the frames, there
  // and back (so that consecutive steps show neighbouring frames).
  static int frame_of(int k) {
    const int period = 2 * (kFrames - 1), i = k % period;
    return i < kFrames ? i : period - i;
  }
  TargetFrame target(int k) const {
    TargetFrame t = test::target_frame(faces.target, frame_of(k));
    t.index = k;
    return t;
  }
  const cv::Mat& frame(int k) const { return frames[size_t(frame_of(k))]; }
  PreparedFrame prepare(FramePreparation& preparation, int k) const {
    const TargetFrame t = target(k);
    return preparation.prepare(frame(k), points[size_t(frame_of(k))], t.camera, t.lighting, k);
  }
};

const SwapScene& swap_scene() {
  static const SwapScene s;
  return s;
}

void BM_FaceSwap720p(benchmark::State& state) {
  const SwapScene& s = swap_scene();
  FaceSwapper swapper(s.model, s.photo, test::source_face(s.model, s.faces.source, 0));
  const std::unique_ptr<FramePreparation> preparation = swapper.make_preparation();
  int k = 0;
  for (; k < SwapOptions{}.appearance_frames; ++k) swapper.swap(s.frame(k), s.target(k));
  for (auto _ : state) {
    state.PauseTiming();  // the preparation runs beside the swap (BM_FramePreparation720p)
    const PreparedFrame prepared = s.prepare(*preparation, k);
    TargetFrame t = s.target(k);
    t.prepared = &prepared;
    state.ResumeTiming();
    benchmark::DoNotOptimize(swapper.swap(s.frame(k), t));
    ++k;
  }
}
BENCHMARK(BM_FaceSwap720p)->Unit(benchmark::kMillisecond);

void BM_FramePreparation720p(benchmark::State& state) {
  const SwapScene& s = swap_scene();
  const FaceSwapper swapper(s.model, s.photo, test::source_face(s.model, s.faces.source, 0));
  const std::unique_ptr<FramePreparation> preparation = swapper.make_preparation();
  int k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.prepare(*preparation, k++));
}
BENCHMARK(BM_FramePreparation720p)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace facecap
