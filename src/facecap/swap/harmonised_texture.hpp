#pragma once
// The source photo's face texture, harmonised with the target's appearance
// (§6.2): the photo unshaded into the skin's UV layout once, then, with each
// of the target's first frames, its albedo adapted to the target's (eq. 6.3:
// a smooth offset on brightness and hue, solved with the target's albedo as
// the boundary condition) and its fine residual histogram-matched to the
// target's (eq. 6.4-6.5). The result carries an alpha channel that fades to
// zero at the skin's boundary, for the render's blend (§6.3).
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/texture_levels.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/albedo_adaptation.hpp"
#include "facecap/swap/face_texture.hpp"

namespace facecap {

struct FaceModel;
struct SourceFace;   // face_swapper.hpp
struct SwapOptions;  // face_swapper.hpp

class HarmonisedTexture {
 public:
  // `skin`: the mesh the texture is laid out on (skin_mesh()); it must
  // outlive this object.
  HarmonisedTexture(const FaceModel& model, const cv::Mat& photo, const SourceFace& source, const TriangleMesh& skin,
                    const SwapOptions& options);

  // One of the target's first frames (`points` in `camera`'s space, the
  // frame's SH lighting; `holes`: the eyes' and the mouth's openings in the
  // image): its unshaded texture joins the target's appearance, and the
  // photo's texture is harmonised again with all of them.
  void add_target_frame(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera,
                        const ShCoeffs& lighting, const std::vector<std::vector<cv::Point>>& holes);
  // Forgets the target frames (they were unshaded under provisional lighting).
  void restart();
  int target_frames() const { return target_frames_; }

  // CV_32FC4: the harmonised albedo (BGR) and alpha; empty before the first
  // target frame.
  const cv::Mat& texture() const { return texture_; }
  const TextureLevels& levels() const { return levels_; }
  // The target's own albedo per skin vertex over its frames so far, and how
  // much of each vertex was seen.
  const Positions& target_vertex_albedo() const { return target_vertex_albedo_; }
  const std::vector<float>& target_vertex_seen() const { return target_vertex_seen_; }

 private:
  void harmonise();

  const TriangleMesh& skin_;
  UvTexelMap map_;
  double noise_sigma_;
  bool match_grade_;
  // The photo's side, fixed once it is unshaded: its albedo per skin vertex,
  // its texture above the noise scale (mid-scale detail scaled by
  // SwapOptions::photo_detail_gain) and the rest, and where it was seen.
  Positions source_vertex_albedo_;
  cv::Mat source_smooth_;    // CV_32FC3
  cv::Mat source_residual_;  // CV_32FC3: the filled albedo less source_smooth_
  cv::Mat source_seen_;      // CV_8U
  cv::Mat alpha_;            // CV_32F: 1 inside, fading to 0 at the skin's boundary
  cv::Mat texture_;
  TextureLevels levels_;
  FaceTexture target_sum_;
  FaceTexture target_first_;
  // The photo's fine residual histogram-matched to target_first_'s (eq. 6.5's
  // noise): it depends on nothing else, so the frames after the first reuse
  // it. Empty until then.
  cv::Mat matched_noise_;
  std::optional<AlbedoAdaptation> adaptation_;  // the last frame's (harmonise())
  int target_frames_ = 0;
  Positions target_vertex_albedo_;
  std::vector<float> target_vertex_seen_;
};

}  // namespace facecap
