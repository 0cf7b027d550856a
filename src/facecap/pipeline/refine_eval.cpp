#include "facecap/pipeline/refine_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "facecap/core/error.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/face_shape_cache.hpp"
#include "facecap/render/photometric.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/render/uv_bake.hpp"
#include "facecap/synth/synth_renderer.hpp"
#include "facecap/synth/wrinkles.hpp"

namespace facecap {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

struct SurfaceImage {
  RasterBuffers buffers;
  cv::Mat normals;
};

SurfaceImage render_surface(const Positions& points, const std::vector<Triangle>& triangles, const PinholeCamera& cam,
                            int w, int h) {
  SurfaceImage s;
  s.buffers.resize(w, h);
  rasterize(points, triangles, cam, s.buffers);
  s.normals = face_normal_image(s.buffers, triangles, points);
  return s;
}

// The truth's wrinkles on one level of the refiner's hierarchy: the synthetic
// displacement function at each vertex's place on the neutral mean face
// (prolonged through the levels with the refiner's own stencils, as the
// renderer prolongs it through its subdivision).
Eigen::VectorXf true_level_displacements(const FaceModel& model, const MeshHierarchy& hierarchy, int level) {
  Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
  const Eigen::MatrixXf place =
      hierarchy.prolong_from_coarse(Positions(neutral.leftCols(regions::kFace.num_vertices())), level);
  Eigen::VectorXf d(place.cols());
  for (Eigen::Index v = 0; v < place.cols(); ++v) d[v] = wrinkle_displacement(Vec3f(place.col(v)));
  return d;
}

// The range of l^T SH(n) over the normals that face the camera (viewer
// frame, n_z >= 0), sampled on a latitude-longitude grid.
std::pair<double, double> shading_range_facing(const ShCoeffs& lighting) {
  constexpr double kPi = 3.14159265358979323846;
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (int i = 0; i <= 45; ++i) {
    const double polar = 0.5 * kPi * i / 45;
    for (int j = 0; j < 180; ++j) {
      const double azimuth = 2 * kPi * j / 180;
      const double s = sh_shade<double>(lighting, std::sin(polar) * std::cos(azimuth),
                                        std::sin(polar) * std::sin(azimuth), std::cos(polar));
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  return {lo, hi};
}

// The finest level's albedo with each observed vertex's shading replaced by
// the value that best matches its own colour in the frame (least squares
// over the three channels), within what a normal facing the camera can
// receive from the frame's lighting: the shading any displacement could
// give that vertex, at best, each vertex on its own. Rendered like the
// refinement, it is the floor of the photometric error that displacements
// reach with this albedo and lighting (colour, texture finer than the level
// and the interpolation between vertices remain).
Positions shading_floor_albedo(const cv::Mat& image, const Refinement& ref, const PinholeCamera& cam) {
  const auto [lo, hi] = shading_range_facing(ref.lighting);
  Positions albedo = ref.albedo;
  for (Eigen::Index v = 0; v < albedo.cols(); ++v) {
    if (!ref.visible[size_t(v)]) continue;
    const Vec3f n = to_viewer_frame(ref.normals.col(v));
    const double shade = sh_shade<double>(ref.lighting, n.x(), n.y(), n.z());
    if (shade <= 0) continue;
    const Vec2f px = cam.project(Vec3f(ref.positions.col(v)));
    const Vec3f observed = sample_bilinear_rgb8(image, px.x(), px.y());
    double num = 0, den = 0;
    for (int c = 0; c < 3; ++c) {
      num += albedo(c, v) * observed[c];
      den += double(albedo(c, v)) * albedo(c, v);
    }
    if (den <= 0) continue;
    const double best = std::clamp(num / den, lo, hi);
    albedo.col(v) *= float(best / shade);
  }
  return albedo;
}

}  // namespace

ShCoeffs scaled_lighting_error_terms(const ShCoeffs& l, const ShCoeffs& truth) {
  const double k = l.squaredNorm() > 0 ? l.dot(truth) / l.squaredNorm() : 1.0;
  return (k * l - truth) / truth.norm();
}

double scaled_lighting_error(const ShCoeffs& l, const ShCoeffs& truth) {
  return scaled_lighting_error_terms(l, truth).norm();
}

double scaled_shading_error(const ShCoeffs& l, const ShCoeffs& truth, const Positions& camera_normals,
                            const std::vector<bool>& visible) {
  std::vector<double> est, tru;
  const Eigen::Index count = std::min<Eigen::Index>(camera_normals.cols(), Eigen::Index(visible.size()));
  for (Eigen::Index i = 0; i < count; ++i) {
    if (!visible[size_t(i)]) continue;
    const Vec3f n = to_viewer_frame(Vec3f(camera_normals.col(i)));
    est.push_back(sh_shade(l, double(n.x()), double(n.y()), double(n.z())));
    tru.push_back(sh_shade(truth, double(n.x()), double(n.y()), double(n.z())));
  }
  if (est.size() < 2) return 0.0;
  double et = 0, ee = 0, mean = 0;
  for (size_t i = 0; i < est.size(); ++i) {
    et += est[i] * tru[i];
    ee += est[i] * est[i];
    mean += tru[i] / double(tru.size());
  }
  const double k = ee > 0 ? et / ee : 1.0;
  double err = 0, spread = 0;
  for (size_t i = 0; i < est.size(); ++i) {
    err += (k * est[i] - tru[i]) * (k * est[i] - tru[i]);
    spread += (tru[i] - mean) * (tru[i] - mean);
  }
  return spread > 0 ? std::sqrt(err / spread) : 0.0;
}

std::vector<bool> face_skin_mask() {
  std::vector<bool> mask(regions::kFace.num_vertices(), false);
  for (int v = regions::kNarrowFace.first_vertex; v <= regions::kNarrowFace.last_vertex; ++v) mask[v] = true;
  return mask;
}

Refiner make_face_refiner(const FaceModel& model, const RefineOptions& options) {
  return Refiner(model.region_polygons(regions::kFace), regions::kFace.num_vertices(), options, face_skin_mask());
}

std::vector<uint8_t> face_albedo_png(const FaceModel& model, const Refiner& refiner) {
  std::vector<uint8_t> png;
  if (!refiner.initialised()) return png;
  const cv::Mat texture = bake_uv_texture(model.region_mesh(regions::kFace), refiner.coarse_albedo());
  return encode_png(texture);
}

RefineOptions lighting_only_refinement() {
  RefineOptions o;
  o.displacements = false;
  o.albedo.frames = 4;
  return o;
}

RefineEvalResult evaluate_refine_synthetic(const FaceModel& model, const RefineEvalOptions& o) {
  SynthOptions so;
  so.frames = o.frames;
  so.seed = o.seed;
  so.width = o.width;
  so.height = o.height;
  so.detail = true;
  so.face_texture = o.face_texture;
  const SynthPerformance perf = make_performance(model, so);
  const SynthRenderer renderer(model, perf);
  const TriangleMesh face = model.region_mesh(regions::kFace);
  Refiner refiner = make_face_refiner(model, o.refine);
  std::mt19937_64 rng(o.seed + 99);

  RefineEvalResult r;
  double refine_ms = 0;
  // Sums of the refined, the coarse and the oracle's normal error over all,
  // detail and flat pixels.
  struct ErrorSums {
    double refined = 0, coarse = 0, oracle = 0;
    long pixels = 0;
    void add(double e_refined, double e_coarse, double e_oracle) {
      refined += e_refined;
      coarse += e_coarse;
      oracle += e_oracle;
      ++pixels;
    }
    double mean_refined() const { return pixels > 0 ? refined / pixels : 0.0; }
    double mean_coarse() const { return pixels > 0 ? coarse / pixels : 0.0; }
    double mean_oracle() const { return pixels > 0 ? oracle / pixels : 0.0; }
  };
  ErrorSums all, detail, flat;
  double depth_sum = 0, depth_coarse_sum = 0;
  KnownShading known;
  if (o.true_shading) known.albedo = renderer.appearance().vertex_albedo.leftCols(face.num_vertices);
  std::vector<bool> seen(face.num_vertices, false);
  Eigen::VectorXf true_wrinkles;  // on the finest level
  Progress progress("refine eval", o.frames, o.quiet);
  for (const SynthFrame& f : perf.frames) {
    const cv::Mat image = renderer.render(f, rng);
    const Positions coarse = to_camera(model.evaluate(perf.identity, f.expression, regions::kFace), f.pose);
    const auto t0 = std::chrono::steady_clock::now();
    known.lighting = f.lighting;
    const Refinement ref = refiner.refine(image, coarse, perf.camera, o.true_shading ? &known : nullptr);
    refine_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const ShCoeffs lighting_error = scaled_lighting_error_terms(ref.lighting, f.lighting);
    r.lighting_error_rel += lighting_error.norm();
    r.lighting_error_terms += lighting_error.cwiseAbs();
    r.shading_error_rel +=
        scaled_shading_error(ref.lighting, f.lighting, vertex_normals(coarse, face.triangles), ref.visible);
    for (int v = 0; v < face.num_vertices; ++v) seen[v] = seen[v] || ref.visible[v];

    // The four surfaces, per pixel.
    const SurfaceImage truth =
        render_surface(renderer.detailed_face(f), renderer.detail_mesh()->triangles, perf.camera, o.width, o.height);
    const int finest = ref.levels - 1;
    const MeshLevel& finest_level = refiner.hierarchy().level(finest);
    const SurfaceImage refined = render_surface(ref.positions, finest_level.triangles, perf.camera, o.width, o.height);
    const SurfaceImage base = render_surface(coarse, face.triangles, perf.camera, o.width, o.height);
    // The oracle: the finest level displaced by the truth's own wrinkles
    // (the hierarchy is fixed after the first frame, and so are they).
    if (true_wrinkles.size() == 0) true_wrinkles = true_level_displacements(model, refiner.hierarchy(), finest);
    const Positions finest_base = refiner.hierarchy().prolong_from_coarse(coarse, finest);
    const SurfaceImage oracle =
        render_surface(displaced_positions(finest_base, level_normals(finest_level, finest_base), true_wrinkles),
                       finest_level.triangles, perf.camera, o.width, o.height);
    for (int y = 0; y < o.height; ++y) {
      for (int x = 0; x < o.width; ++x) {
        const size_t i = size_t(y) * o.width + x;
        if (!truth.buffers.covered(x, y) || !refined.buffers.covered(x, y) || !base.buffers.covered(x, y) ||
            !oracle.buffers.covered(x, y))
          continue;
        const cv::Vec3f nt = truth.normals.at<cv::Vec3f>(y, x), nr = refined.normals.at<cv::Vec3f>(y, x),
                        nc = base.normals.at<cv::Vec3f>(y, x), no = oracle.normals.at<cv::Vec3f>(y, x);
        auto angle = [](const cv::Vec3f& a, const cv::Vec3f& b) {
          const double c = a.dot(b) / std::max(1e-12, double(cv::norm(a) * cv::norm(b)));
          return std::acos(std::clamp(c, -1.0, 1.0)) * kRadToDeg;
        };
        const double e_refined = angle(nr, nt), e_coarse = angle(nc, nt), e_oracle = angle(no, nt);
        all.add(e_refined, e_coarse, e_oracle);
        (e_coarse > RefineEvalResult::kDetailAngleDeg ? detail : flat).add(e_refined, e_coarse, e_oracle);
        depth_sum += 10.0 * std::abs(refined.buffers.depth[i] - truth.buffers.depth[i]);
        depth_coarse_sum += 10.0 * std::abs(base.buffers.depth[i] - truth.buffers.depth[i]);
      }
    }
    ++r.frames;
    r.levels = ref.levels;
    r.finest_vertices = static_cast<int>(ref.positions.cols());
    progress.update(r.frames);
  }
  progress.finish();
  r.lighting_error_rel /= std::max(1, r.frames);
  r.lighting_error_terms /= std::max(1, r.frames);
  r.shading_error_rel /= std::max(1, r.frames);
  r.refine_ms_per_frame = refine_ms / std::max(1, r.frames);
  if (all.pixels > 0) {
    r.normal_error_deg = all.mean_refined();
    r.normal_error_coarse_deg = all.mean_coarse();
    r.detail_pixel_fraction = double(detail.pixels) / all.pixels;
    r.normal_error_detail_deg = detail.mean_refined();
    r.normal_error_detail_coarse_deg = detail.mean_coarse();
    r.normal_error_flat_deg = flat.mean_refined();
    r.normal_error_flat_coarse_deg = flat.mean_coarse();
    r.normal_error_oracle_deg = all.mean_oracle();
    r.normal_error_detail_oracle_deg = detail.mean_oracle();
    r.vertex_error_mm = depth_sum / all.pixels;
    r.vertex_error_coarse_mm = depth_coarse_sum / all.pixels;
  }
  std::vector<double> est, tru;
  const Positions& albedo = refiner.coarse_albedo();
  for (int v = 0; v < face.num_vertices; ++v) {
    if (!seen[v]) continue;
    for (int c = 0; c < 3; ++c) {
      est.push_back(albedo(c, v));
      tru.push_back(renderer.appearance().vertex_albedo(c, v));
    }
  }
  r.albedo_corr = pearson_correlation(est, tru);
  return r;
}

RefineVideoResult evaluate_refine_video(const FaceModel& model, const std::string& path, const CaptureOptions& capture,
                                        const RefineOptions& refine) {
  auto source = open_input(path);
  const InputInfo info = source->info();
  const TriangleMesh face = model.region_mesh(regions::kFace);
  const std::vector<Triangle> skin = masked_triangles(face.triangles, face_skin_mask());
  Refiner refiner = make_face_refiner(model, refine);
  FaceShapeCache face_shape(model, regions::kFace);
  RefineVideoResult r;
  double refine_ms = 0;
  CaptureOptions c = capture;
  c.keep_images = true;
  run_capture(model, *source, c, [&](const CapturedFrame& f) {
    if (f.status == TrackStatus::kLost) return;
    const PinholeCamera cam = PinholeCamera::centered(f.fit.focal, info.width, info.height);
    const Positions coarse =
        to_camera(face_shape.evaluate(f.identity.identity.cast<float>(), f.fit.expression), f.fit.pose);
    const auto t0 = std::chrono::steady_clock::now();
    const Refinement ref = refiner.refine(f.image, coarse, cam);
    refine_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const PhotometricError coarse_error = photometric_error(
        f.image, coarse, skin, vertex_normals(coarse, face.triangles), refiner.coarse_albedo(), ref.lighting, cam);
    const std::vector<Triangle> refined_skin =
        masked_triangles(refiner.hierarchy().level(ref.levels - 1).triangles, ref.data_mask);
    const PhotometricError refined_error =
        photometric_error(f.image, ref.positions, refined_skin, ref.normals, ref.albedo, ref.lighting, cam);
    r.photometric_coarse += coarse_error.mean_abs;
    r.photometric_refined += refined_error.mean_abs;
    r.photometric_shading_floor += photometric_error(f.image, ref.positions, refined_skin, ref.normals,
                                                     shading_floor_albedo(f.image, ref, cam), ref.lighting, cam)
                                       .mean_abs;
    ++r.frames;
  });
  if (r.frames > 0) {
    r.photometric_coarse /= r.frames;
    r.photometric_refined /= r.frames;
    r.photometric_shading_floor /= r.frames;
    r.refine_ms_per_frame = refine_ms / r.frames;
  }
  return r;
}

}  // namespace facecap
