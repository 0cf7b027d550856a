#pragma once
// Shading-based refinement of a tracked face (§4.2-4.3), one frame at a time:
// the mesh hierarchy is built on the first frame; each frame then estimates
// the SH lighting on the coarsest level (with the previous frame's
// displacements, M_d = M + d_{t-1} N), updates the albedo during the first
// frames (then holds it), and solves the displacements level by level from
// coarse to fine, each level starting from the prolonged coarser solution.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/refine/albedo.hpp"
#include "facecap/refine/displacement_backend.hpp"
#include "facecap/refine/displacement_solver.hpp"
#include "facecap/refine/lighting.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/refine/vertex_sampler.hpp"

namespace facecap {

struct RefineOptions {
  bool displacements = true;  // false: lighting and albedo only (the finest level is the coarse mesh)
  // Lighting/albedo alternations over all the albedo frames so far, at the
  // frame that fixes the albedo, and at each earlier albedo frame (which
  // starts from the previous one's solution, so is nearly there). On the
  // whole of address_720p_a, interim rounds 4 / 2 / 1 give refined
  // photometric errors 4.787 / 4.787 / 4.809; the albedo phase costs 40 /
  // 22 / 13 albedo solves over its 10 frames.
  int albedo_rounds = 4;
  int albedo_rounds_interim = 2;
  // Rings of observations dropped next to unobserved vertices before the
  // displacement solve (erode_observations); the solve still covers them.
  // Two rings: the bilinear sample's footprint and the normal's one-ring. On
  // synthetic wrinkles with the true lighting and albedo, 0 / 1 / 2 / 3 rings
  // leave 0.36 / 0.21 / 0.13 / 0.09 deg of false normal detail where the truth
  // has none; more rings mostly refine less (on address_720p_a the refined
  // photometric error went 6.6 / 6.8 / 6.9 for 0 / 1 / 2 rings, measured
  // before the depth test allowed for slopes).
  int data_margin_rings = 2;
  // The same for the lighting and albedo on the coarsest level, where it also
  // drops the rims of the eye and mouth holes (their samples read the eye
  // whites, the teeth). On 12 synthetic frames (`eval refine --synthetic 12`,
  // seeds 1-4) the lighting error with 0 / 1 / 2 rings is 0.14 / 0.39 / 0.27 /
  // 0.36, 0.16 / 0.26 / 0.15 / 0.27 and 0.15 / 0.21 / 0.12 / 0.25; eroding
  // only the lighting's samples (the albedo reading every vertex) gave 0.23 /
  // 0.18 / 0.32 / 0.14. On address_720p_a (40 frames) the refined photometric
  // error goes 4.65 -> 4.74: the rims' albedo is now the smooth prior's.
  int shading_margin_rings = 2;
  // The displacement solve reads only vertices facing the camera within 45
  // degrees (cos >= 0.7; drop_oblique_observations); the lighting and albedo
  // read every visible vertex (the oblique ones are what pin the lighting's
  // n_z terms). On 12 synthetic frames with wrinkles (`eval refine
  // --synthetic 12`, seeds 1 / 2) the refined normal error with all / cos 0.5
  // / cos 0.7 is 1.90 / 1.49 / 1.11 and 1.04 / 0.92 / 0.83 degrees (coarse
  // 0.72 and 0.64); seed 2's albedo correlation 0.89 / 0.99 / 0.99: oblique
  // displacements also corrupt the next frame's M_d. On address_720p_a (30
  // frames) the refined photometric error is 4.29 / 4.41 / 4.50.
  double displacement_min_facing = 0.7;
  // Where the vertex sampling (the depth test and the colours), the albedo's
  // conjugate gradients and the displacement solve run (the lighting's 9 x 9
  // normal equations are formed and solved on the CPU): CUDA when this build
  // has it and a GPU answers.
  ComputeDevice device = default_compute_device();
  // Called with each displacement problem before it is solved (frame index,
  // level, problem, starting d): `eval refine --save-problems` writes them.
  std::function<void(int frame, int level, const DisplacementProblem&, const Eigen::VectorXf& start)>
      on_displacement_problem;
  HierarchyOptions hierarchy;
  LightingOptions lighting;
  AlbedoOptions albedo;
  DisplacementOptions displacement;
};

// Milliseconds per part of one frame's refinement.
struct RefineTimings {
  double pyramid_ms = 0;
  double lighting_ms = 0;  // the coarsest level's normals and samples, and the estimate
  double albedo_ms = 0;
  std::vector<double> level_ms;  // per level: its base, samples, masks and displacement solve
  // Parts of the above: every vertex sampling of the frame (lighting and
  // levels), and each level's displacement solve alone.
  double sampling_ms = 0;
  std::vector<double> solve_ms;
  bool albedo_fixed = false;  // the albedo was fixed before this frame (no albedo solve in it)
};

struct Refinement {
  ShCoeffs lighting = ShCoeffs::Zero();
  Positions positions;           // refined finest level, camera space (cm)
  Eigen::VectorXf displacement;  // finest level: d of M_d = M + d N (eq. 4.11), cm along the base's outward normal
  Positions normals;             // of the refined finest level
  Positions albedo;              // finest level, RGB
  std::vector<bool> visible;     // finest level vertices seen in this frame (and in the data mask)
  std::vector<bool> data_mask;   // finest level vertices the estimators used
  int levels = 0;
  bool albedo_final = false;  // the albedo was fixed by this frame or before it: later lightings are final
  RefineTimings timings;
};

// The triangles whose three vertices are all in `mask`.
std::vector<Triangle> masked_triangles(const std::vector<Triangle>& triangles, const std::vector<bool>& mask);

// Lighting and coarsest-level albedo known from elsewhere (a synthetic
// render's truth): the displacement solve uses them instead of the
// estimates, which are still made and reported. `eval refine --true-shading`
// measures the displacement solve alone this way.
struct KnownShading {
  ShCoeffs lighting = ShCoeffs::Zero();
  Positions albedo;  // 3 x N RGB on the coarse mesh
};

// A frame refined through its coarsest level (Refiner::begin_frame), whose
// finer levels Refiner::finish_frame solves.
struct PendingFrame {
  std::vector<cv::Mat> pyramid;  // the frame, then each level half the size
  Positions coarse, coarse_normals;
  PinholeCamera camera;
  ShCoeffs lighting_used = ShCoeffs::Zero();  // the estimate, or the known lighting
  int frame_index = 0;                        // since the refiner's shot began
  // The last level solved: its base surface, albedo and displacements.
  Eigen::MatrixXf base, albedo;
  Eigen::VectorXf d;
  std::optional<VertexSamples> undisplaced_samples;  // the lighting's, when they are the level's too
  Refinement out;

  // Mesh level l pairs with the image 2^(levels - 1 - l) times smaller.
  const cv::Mat& image_for(int l) const { return pyramid[out.levels - 1 - l]; }
  PinholeCamera camera_for(int l) const { return camera.resized(1.0 / double(1 << (out.levels - 1 - l))); }
};

class Refiner {
 public:
  // polygons / num_vertices: the coarse mesh (the face region). data_mask:
  // the coarse vertices whose colours the estimators may use (the skin: not
  // the neck and shirt, hairline or ears the face region also covers); empty
  // = all.
  Refiner(std::vector<Polygon> polygons, int num_vertices, RefineOptions options = {},
          std::vector<bool> data_mask = {});

  // Refines one frame: `coarse` are the coarse mesh's camera-space positions
  // (the tracked face), `image` the BGR 8-bit frame, `camera` its intrinsics.
  Refinement refine(const cv::Mat& image, const Positions& coarse, const PinholeCamera& camera,
                    const KnownShading* known = nullptr);

  // refine() in two halves, for a pipeline (RefineStage): begin_frame() makes
  // the pyramid and solves the lighting, the albedo and the coarsest level's
  // displacements; finish_frame() the finer levels. Frame t's finish_frame
  // may run on another thread while frame t + 1's begin_frame runs (the
  // finer levels depend on the frame's coarsest level and on their own last
  // solution, nothing else); each half runs in frame order, and the results
  // are refine()'s.
  PendingFrame begin_frame(const cv::Mat& image, const Positions& coarse, const PinholeCamera& camera,
                           const KnownShading* known = nullptr);
  Refinement finish_frame(PendingFrame&& frame);

  // A shot cut (shot_cut.hpp): the albedo is estimated again over the next
  // frames, and the lighting and displacements start afresh; the hierarchy,
  // built on the first frame, is kept (its meshes stay one topology). Not
  // while a finish_frame() runs.
  void start_shot();

  // Makes the samplers and displacement backends of both halves now rather
  // than at the first frame: on a GPU this creates the CUDA context and
  // streams (a few hundred milliseconds), which RefineStage does while
  // capture solves the identity over its first frames.
  void prepare_devices();

  bool initialised() const { return hierarchy_.num_levels() > 0; }
  const MeshHierarchy& hierarchy() const { return hierarchy_; }
  // The albedo at the coarsest level (3 x N RGB) and whether it is final.
  const Positions& coarse_albedo() const;
  bool albedo_fixed() const { return albedo_ && albedo_->fixed(); }

 private:
  std::vector<Polygon> polygons_;
  int num_vertices_;
  std::vector<bool> data_mask_;
  RefineOptions options_;
  MeshHierarchy hierarchy_;
  std::unique_ptr<AlbedoEstimator> albedo_;
  // Solves level l of a frame into it: its base, samples, masks and displacements.
  void solve_level(int l, PendingFrame& frame);

  // Half `half`'s device objects, made when first asked for.
  VertexSampler& sampler(int half);
  DisplacementBackend& displacement(int half);

  // Per half of a frame (the coarsest level; the finer ones), made when first used.
  std::array<std::unique_ptr<DisplacementBackend>, 2> displacement_;
  std::array<std::unique_ptr<VertexSampler>, 2> sampler_;
  std::optional<ShCoeffs> lighting_;
  // Per level, last frame's displacements: level 0 begin_frame's, the finer finish_frame's.
  std::vector<Eigen::VectorXf> previous_;
  // The albedo frames' coarsest-level samples and normals, kept until the
  // albedo is fixed: lighting and albedo are solved alternately over all of them.
  struct AlbedoFrame {
    VertexSamples samples;
    Positions normals;
    ShCoeffs lighting = ShCoeffs::Zero();
  };
  std::vector<AlbedoFrame> albedo_frames_;
  int frame_count_ = 0;
  std::vector<RasterBuffers> raster_;  // per level, reused across frames
  // Per level, fixed with the hierarchy: the data mask and its triangles.
  std::vector<std::vector<bool>> level_masks_;
  std::vector<std::vector<Triangle>> level_skin_;
};

}  // namespace facecap
