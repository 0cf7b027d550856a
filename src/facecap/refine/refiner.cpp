#include "facecap/refine/refiner.hpp"

#include <chrono>
#include <optional>
#include <string>

#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"

namespace facecap {

Refiner::Refiner(std::vector<Polygon> polygons, int num_vertices, RefineOptions options, std::vector<bool> data_mask)
    : polygons_(std::move(polygons)), num_vertices_(num_vertices), data_mask_(std::move(data_mask)), options_(options) {
  if (data_mask_.empty()) data_mask_.assign(num_vertices_, true);
}

std::vector<Triangle> masked_triangles(const std::vector<Triangle>& triangles, const std::vector<bool>& mask) {
  std::vector<Triangle> out;
  for (const Triangle& t : triangles)
    if (mask[t[0]] && mask[t[1]] && mask[t[2]]) out.push_back(t);
  return out;
}

namespace {
// Vertices outside the mask are not observations.
void apply_mask(VertexSamples& s, const std::vector<bool>& mask) {
  s.visible_count = 0;
  for (size_t i = 0; i < s.visible.size(); ++i) {
    s.visible[i] = s.visible[i] && mask[i];
    s.visible_count += s.visible[i];
  }
}
}  // namespace

const Positions& Refiner::coarse_albedo() const {
  static const Positions empty;
  return albedo_ ? albedo_->albedo() : empty;
}

void Refiner::start_shot() {
  if (!initialised()) return;
  albedo_ = std::make_unique<AlbedoEstimator>(hierarchy_.level(0), options_.albedo, options_.device);
  albedo_frames_.clear();
  frame_count_ = 0;
  lighting_.reset();
  for (Eigen::VectorXf& d : previous_) d = Eigen::VectorXf();
}

VertexSampler& Refiner::sampler(int half) {
  if (!sampler_[half]) sampler_[half] = make_vertex_sampler(options_.device);
  return *sampler_[half];
}

DisplacementBackend& Refiner::displacement(int half) {
  if (!displacement_[half]) displacement_[half] = make_displacement_backend(options_.device);
  return *displacement_[half];
}

void Refiner::prepare_devices() {
  for (int half = 0; half < 2; ++half) {
    sampler(half);
    if (options_.displacements) displacement(half);
  }
}

Refinement Refiner::refine(const cv::Mat& image, const Positions& coarse, const PinholeCamera& camera,
                           const KnownShading* known) {
  return finish_frame(begin_frame(image, coarse, camera, known));
}

PendingFrame Refiner::begin_frame(const cv::Mat& image, const Positions& coarse, const PinholeCamera& camera,
                                  const KnownShading* known) {
  if (known && known->albedo.cols() != num_vertices_)
    throw Error("known albedo has " + std::to_string(known->albedo.cols()) + " vertices, the mesh " +
                std::to_string(num_vertices_));
  if (!initialised()) {
    HierarchyOptions ho = options_.hierarchy;
    if (!options_.displacements) ho.levels = 1;
    hierarchy_ = MeshHierarchy::build(polygons_, num_vertices_, coarse, camera, ho);
    albedo_ = std::make_unique<AlbedoEstimator>(hierarchy_.level(0), options_.albedo, options_.device);
    previous_.assign(hierarchy_.num_levels(), Eigen::VectorXf());
    raster_.assign(hierarchy_.num_levels(), RasterBuffers());
    level_masks_.clear();
    level_skin_.clear();
    for (int l = 0; l < hierarchy_.num_levels(); ++l) {
      level_masks_.push_back(hierarchy_.prolong_mask(data_mask_, l));
      level_skin_.push_back(masked_triangles(hierarchy_.level(l).triangles, level_masks_.back()));
    }
  }
  const int levels = hierarchy_.num_levels();
  PendingFrame f;
  Refinement& out = f.out;
  out.levels = levels;
  out.timings.level_ms.assign(levels, 0.0);
  out.timings.solve_ms.assign(levels, 0.0);
  out.timings.albedo_fixed = albedo_->fixed();
  f.coarse = coarse;
  f.camera = camera;
  f.frame_index = frame_count_;

  // Mesh level l pairs with the image 2^(levels - 1 - l) times smaller.
  auto t0 = std::chrono::steady_clock::now();
  f.pyramid = image_pyramid(image, levels);
  out.timings.pyramid_ms = ms_since(t0);

  // Lighting on the coarsest level with last frame's displacements (M_d = M + d N).
  t0 = std::chrono::steady_clock::now();
  const MeshLevel& level0 = hierarchy_.level(0);
  f.coarse_normals = level_normals(level0, coarse);
  Positions md = coarse;
  if (previous_[0].size() == coarse.cols()) md = displaced_positions(coarse, f.coarse_normals, previous_[0]);
  const Positions md_normals = level_normals(level0, md);
  const auto sampling_start = std::chrono::steady_clock::now();
  VertexSamples samples0 =
      sampler(0).sample(f.image_for(0), md, md_normals, md, level_skin_[0], f.camera_for(0), raster_[0]);
  out.timings.sampling_ms += ms_since(sampling_start);
  apply_mask(samples0, data_mask_);
  // Without displacements the displacement pass below has this level, with
  // d = 0, the same depth mesh and the same mask: its samples are these,
  // before the lighting's erosion, and need not be drawn again.
  if (!options_.displacements && levels == 1) f.undisplaced_samples = samples0;
  erode_observations(samples0, level0.rings, options_.shading_margin_rings, level0.boundary);
  if (albedo_->frames() == 0 && !lighting_) albedo_->initialise_uniform(samples0);
  const ShCoeffs lighting = estimate_lighting(samples0, md_normals, albedo_->albedo(), lighting_, options_.lighting);
  out.timings.lighting_ms = ms_since(t0);

  // Albedo during the first frames: lighting and albedo alternately over all
  // the albedo frames so far (a bilinear problem; one pass per frame would
  // bake the first frame's lighting error into the albedo).
  t0 = std::chrono::steady_clock::now();
  ShCoeffs frame_lighting = lighting;
  const bool albedo_frame = !albedo_->fixed() && frame_count_ % std::max(1, options_.albedo.interval) == 0;
  ++frame_count_;
  if (albedo_frame) {
    albedo_frames_.push_back({samples0, md_normals, lighting});
    const bool fixing_frame = static_cast<int>(albedo_frames_.size()) >= options_.albedo.frames;
    const int rounds = fixing_frame ? options_.albedo_rounds : options_.albedo_rounds_interim;
    for (int round = 0; round < rounds; ++round) {
      albedo_->clear_data();
      for (AlbedoFrame& a : albedo_frames_) {
        if (round > 0)
          a.lighting = estimate_lighting(a.samples, a.normals, albedo_->albedo(), std::nullopt, options_.lighting);
        albedo_->add_frame(a.samples, a.normals, a.lighting);
      }
      albedo_->solve();
    }
    frame_lighting = estimate_lighting(samples0, md_normals, albedo_->albedo(), lighting_, options_.lighting);
    if (albedo_->fixed()) albedo_frames_.clear();
  }
  out.timings.albedo_ms = ms_since(t0);
  lighting_ = frame_lighting;
  out.lighting = frame_lighting;
  out.albedo_final = albedo_->fixed();
  f.lighting_used = known ? known->lighting : frame_lighting;

  // The coarsest level's displacements.
  f.base = coarse;
  f.albedo = known ? known->albedo : albedo_->albedo();
  solve_level(0, f);
  return f;
}

Refinement Refiner::finish_frame(PendingFrame&& f) {
  for (int l = 1; l < f.out.levels; ++l) solve_level(l, f);
  return std::move(f.out);
}

void Refiner::solve_level(int l, PendingFrame& f) {
  const auto t0 = std::chrono::steady_clock::now();
  Refinement& out = f.out;
  const int levels = out.levels;
  const MeshLevel& level = hierarchy_.level(l);
  // Each level's device objects serve one of the frame's two halves, so that
  // they may run on two threads at once.
  const int half = l == 0 ? 0 : 1;
  Eigen::VectorXf prolonged;
  if (l > 0) {
    f.base = hierarchy_.prolong(f.base, l);
    f.albedo = hierarchy_.prolong(f.albedo, l);
    prolonged = hierarchy_.prolong(Eigen::MatrixXf(f.d.transpose()), l).transpose();
  }
  DisplacementProblem problem;
  problem.level = &level;
  problem.base = f.base;
  // Level 0's base is the coarse mesh, whose normals the lighting computed.
  problem.base_normals = l == 0 ? f.coarse_normals : level_normals(level, problem.base);
  problem.albedo = f.albedo;
  problem.lighting = f.lighting_used;
  const std::vector<bool>& mask = level_masks_[l];
  // Depth from the coarse mesh, whose surface every level's base is
  // (unless the smoothing mask moved the new vertices off it).
  const bool coarse_depth = !options_.hierarchy.smoothing_mask;
  const auto sampling_start = std::chrono::steady_clock::now();
  VertexSamples samples = f.undisplaced_samples
                              ? std::move(*f.undisplaced_samples)
                              : sampler(half).sample(f.image_for(l), problem.base, problem.base_normals,
                                                     coarse_depth ? f.coarse : problem.base,
                                                     level_skin_[coarse_depth ? 0 : l], f.camera_for(l), raster_[l]);
  f.undisplaced_samples.reset();
  out.timings.sampling_ms += ms_since(sampling_start);
  apply_mask(samples, mask);
  drop_oblique_observations(samples, problem.base, problem.base_normals, float(options_.displacement_min_facing));
  // Solve where skin is seen, with two rings of margin; elsewhere d = 0.
  problem.active = grow_by_rings(samples.visible, level.rings, 2);
  erode_observations(samples, level.rings, options_.data_margin_rings, level.boundary);
  problem.samples = &samples;
  problem.prolonged = prolonged;
  if (previous_[l].size() == level.num_vertices) problem.previous = previous_[l];
  // Start from the coarser level's solution, or at level 0 from last frame's.
  f.d = l > 0 ? prolonged : (problem.previous.size() ? problem.previous : Eigen::VectorXf::Zero(level.num_vertices));
  if (options_.displacements) {
    if (options_.on_displacement_problem) options_.on_displacement_problem(f.frame_index, l, problem, f.d);
    const auto solve_start = std::chrono::steady_clock::now();
    displacement(half).solve(problem, f.d, options_.displacement);
    out.timings.solve_ms[l] = ms_since(solve_start);
  }
  previous_[l] = f.d;
  if (l == levels - 1) {
    out.positions = displaced_positions(problem.base, problem.base_normals, f.d);
    out.displacement = f.d;
    out.normals = level_normals(level, out.positions);
    out.albedo = f.albedo;
    out.visible = samples.visible;
    out.data_mask = mask;
  }
  out.timings.level_ms[l] = ms_since(t0);
}

}  // namespace facecap
