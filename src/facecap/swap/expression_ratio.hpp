#pragma once
// The target's own change of appearance since its appearance frames, texel
// by texel, as a gain on the new face (a departure from the paper, beside
// the wrinkle prediction of §6.1.2; the classic expression ratio image).
// Each frame the target face is unshaded into a UV texture about a
// millimetre per texel (unshade_face); its log colour (per channel, or its
// luminance) less that of the appearance frames' mean is the change: folds that deepen with a smile, the
// shadow a lip casts, skin that stretches. It is band-passed between
// `fine_mm` (image noise) and `coarse_mm` (the scale residual_shading.hpp
// already covers), so neither the overall level nor the noise moves, and
// gated where the target's own texture has an edge (lips, brows, moles):
// there a change is mostly the tracking sliding the edge across the surface,
// which on another face would show as a ghost of the target's features.
// The target's static look cancels in the ratio; only its motion remains.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/face_texture.hpp"

namespace facecap {

struct ExpressionRatioOptions {
  float texel_mm = 1.0f;    // the ratio's UV grid: about the image's resolution at 720p
  float fine_mm = 1.0f;     // Gaussian sigma below which the change is noise
  float coarse_mm = 20.0f;  // Gaussian sigma above which it is residual shading's
  // Edge gate: the change is kept in full where the reference texture's log
  // colour changes by less than this per millimetre (at the fine scale,
  // largest over the channels, taken over the fine blur's footprint), and
  // falls off as 1 / (1 + (gradient / this)^4) above it. Self-swap (`eval
  // swap --self address_720p_a.mp4`) median / mean at 0.1 / 0.15: 3.0 /
  // 4.47, 2.67 / 4.19; with the square at 0.2 / 0.3: 2.67 / 4.16, 2.67 /
  // 4.05, in luminance with no gate 3.0 / 4.19 (README). 0.15 keeps 8 % of
  // a lip-like edge slid 1.5 texels (the square at 0.2, 15 %).
  float edge_log_per_mm = 0.15f;
  float max_gain = 1.5f;  // gains are clamped to [1 / max_gain, max_gain]
  // A gain per BGR channel rather than one for the luminance: the shadow in
  // a fold is redder than the skin's, and the lips' edge is one of colour.
  // Self-swap as above, both with the squared gate at 0.2 on the luminance
  // gradient (before it covered the blur's footprint): 2.67 / 4.04 against
  // 3.0 / 4.23.
  bool colour = true;
};

class ExpressionRatio {
 public:
  // `skin`: the face's triangles with UVs; `mm_per_uv`: millimetres on the
  // face per unit of UV (millimetres_per_uv()).
  ExpressionRatio(const TriangleMesh& skin, double mm_per_uv, ExpressionRatioOptions options = {});

  // Unshades one target frame into the ratio's grid (unshade_face's
  // arguments; non-skin texels dropped).
  FaceTexture unshade(const cv::Mat& frame, const Positions& target_points, const PinholeCamera& camera,
                      const ShCoeffs& lighting, const std::vector<std::vector<cv::Point>>& excluded) const;
  // The appearance frames: their mean is the reference the change is measured from.
  void clear_reference();
  void add_reference(const FaceTexture& texture);

  // The gain (CV_32F, or CV_32FC3 BGR with `colour`; grid_size() square over UV [0, 1]^2, row 0 at v = 1)
  // for a frame unshaded by unshade(); all ones before any reference.
  cv::Mat gains(const FaceTexture& frame) const;

  int grid_size() const { return grid_.map.size; }

 private:
  ExpressionRatioOptions options_;
  TriangleMesh skin_;
  MillimetreGrid grid_;  // about options_.texel_mm per texel
  FaceTexture reference_sum_;
  // Of the reference so far (updated by add_reference): its log colour (or
  // luminance), where it was seen, and the edge gate it gives.
  cv::Mat log_reference_, seen_reference_, gate_;
};

}  // namespace facecap
