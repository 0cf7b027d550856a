#pragma once
// `facecap eval refine`: the shading-based refinement measured.
//  - synthetic: `facecap synth --detail` renders (known albedo, SH lighting
//    and wrinkle displacements) refined from their true coarse geometry (or
//    the tracked one): lighting error up to the albedo scale, albedo
//    correlation, and normal and depth errors of the refined and the coarse
//    surface against the true detailed surface, per pixel.
//  - video: real footage tracked and refined: photometric error of the coarse
//    and the refined mesh rendered with the recovered albedo and lighting.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/pipeline/capture_session.hpp"
#include "facecap/refine/refiner.hpp"

namespace facecap {

struct RefineEvalOptions {
  int frames = 16;
  uint64_t seed = 1;
  int width = 1280;
  int height = 720;
  RefineOptions refine;
  // Solve the displacements with the render's own lighting and albedo (the
  // estimates are still made and reported): the solver's accuracy alone.
  bool true_shading = false;
  // The renders' skin (SynthOptions::face_texture); empty: painted.
  cv::Mat face_texture;
  bool quiet = false;
};

struct RefineEvalResult {
  int frames = 0;
  int levels = 0;
  int finest_vertices = 0;
  double lighting_error_rel = 0;  // scaled_lighting_error, mean over frames
  // Where that error lies: each coefficient's |scaled_lighting_error_terms|,
  // mean over frames, in SH order (1, x, y, z, xy, xz, yz, x^2 - y^2,
  // 3 z^2 - 1). Most of it is in the n_z term, whose trade with the albedo's
  // fall-off toward the face's rim a turning head hardly shows (docs/open-bars.md).
  ShCoeffs lighting_error_terms = ShCoeffs::Zero();
  // The same lighting judged by the shading it gives the face's visible
  // vertices' normals (scaled_shading_error): well conditioned where the
  // coefficients are not.
  double shading_error_rel = 0;
  double albedo_corr = 0;  // Pearson, RGB of the vertices seen
  double normal_error_deg =
      0;  // refined finest level vs the true detailed surface: geometric (triangle) normals per pixel
  double normal_error_coarse_deg = 0;
  // The same split by where the true surface has detail: pixels whose true
  // normal lies more than kDetailAngleDeg from the coarse mesh's (the
  // wrinkles), and the rest (flat skin, where any detail is false).
  static constexpr double kDetailAngleDeg = 1.0;
  double detail_pixel_fraction = 0;
  double normal_error_detail_deg = 0;
  double normal_error_detail_coarse_deg = 0;
  double normal_error_flat_deg = 0;
  double normal_error_flat_coarse_deg = 0;
  // The oracle: the finest level displaced by the truth's own wrinkle
  // function, scored the same way. What the hierarchy can represent, so the
  // floor under normal_error_deg that a perfect solve would reach.
  double normal_error_oracle_deg = 0;
  double normal_error_detail_oracle_deg = 0;
  double vertex_error_mm = 0;  // |depth - true depth| per pixel
  double vertex_error_coarse_mm = 0;
  double refine_ms_per_frame = 0;
};

// The refinement's data mask on the face region: the narrow face area of
// FACTS.md (skin; the face region also covers neck, hairline and ears).
std::vector<bool> face_skin_mask();
// A refiner for the model's face region with that mask.
Refiner make_face_refiner(const FaceModel& model, const RefineOptions& options);
// Lighting and albedo only (no displacements), with the albedo over 4 frames
// instead of 10: for the edits, where the lighting feeds a shading ratio or
// a re-shading whose scale only has to be consistent within one video.
RefineOptions lighting_only_refinement();
// A face refiner's albedo baked into the ICT UV layout (bake_uv_texture) as
// PNG bytes: `track --refine`'s albedo.png and the face texture of the
// animated glTF. Empty until the refiner has an albedo.
std::vector<uint8_t> face_albedo_png(const FaceModel& model, const Refiner& refiner);

// (k l - l_true) / ||l_true||, k the best scale (albedo times lighting is
// only determined up to a common factor): the error of each coefficient.
ShCoeffs scaled_lighting_error_terms(const ShCoeffs& l, const ShCoeffs& truth);
// Its norm, ||k l - l_true|| / ||l_true||.
double scaled_lighting_error(const ShCoeffs& l, const ShCoeffs& truth);
// The lighting judged by the shading it gives `camera_normals` where
// `visible`: RMS of k s - s_true (s = l . SH(n), k the best scale) over the
// RMS of s_true about its mean. Seen from one side, 1, n_z and 3 n_z^2 - 1
// are nearly collinear, so coefficient vectors far apart shade a face alike:
// this measures what an image determines.
double scaled_shading_error(const ShCoeffs& l, const ShCoeffs& truth, const Positions& camera_normals,
                            const std::vector<bool>& visible);

RefineEvalResult evaluate_refine_synthetic(const FaceModel& model, const RefineEvalOptions& options);

struct RefineVideoResult {
  int frames = 0;
  double photometric_coarse =
      0;  // mean absolute difference, 0-255, over skin pixels (narrow face area), mean over frames
  double photometric_refined = 0;
  // The refined finest level with each observed vertex's grey level fitted to
  // its own colour: the floor one displacement per vertex can reach.
  double photometric_shading_floor = 0;
  double refine_ms_per_frame = 0;
};

RefineVideoResult evaluate_refine_video(const FaceModel& model, const std::string& path, const CaptureOptions& capture,
                                        const RefineOptions& refine);

}  // namespace facecap
