#pragma once
// Face swapping (chapter 6): the source portrait's identity with the
// target's per-frame expression (§6.1.1), the source appearance harmonised
// with the target's (albedo adaptation, eq. 6.3, and noise matching,
// eq. 6.4-6.5, both computed over the first target frames and then held),
// rendered under the target's pose and SH lighting (eq. 6.6-6.7), and the
// colour and low-pass shading that lighting leaves unexplained and the
// target's own fine change of appearance since its first frames (departures
// from the paper: light_colour.hpp, residual_shading.hpp,
// expression_ratio.hpp), into the
// target frame after warping its background to the new face outline, and
// blended with an alpha map built in UV space that fades toward the
// boundary of the face (§6.3).
#include <memory>
#include <opencv2/core.hpp>
#include <optional>

#include "facecap/core/camera.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/swap/size_match.hpp"

namespace facecap {

struct PreparedFrame;    // frame_preparation.hpp
class FramePreparation;  // frame_preparation.hpp

struct SwapOptions {
  int texture_size = 1024;  // UV texture of the face
  // Target frames over which the appearance is harmonised, then held,
  // counted from the first with final lighting (TargetFrame::lighting_final).
  int appearance_frames = 5;
  float fade_texels = 40.0f;  // width of the alpha fade at the face boundary, in texels
  // Near the outline, where the surface turns away, alpha fades in from
  // this cosine between the normal and the view ray over the next 0.3
  // (silhouette_fade.hpp).
  float silhouette_fade_start = 0.3f;
  double noise_sigma = 2.0;     // texels: the residual of eq. 6.4 is what a blur of this size removes
  bool warp_background = true;  // §6.3; off: the new face is laid over the unwarped frame
  // §6.1.2: carry the target's fine-scale motion (wrinkles that come and go
  // with its expression) onto the new face; needs each target frame's
  // refined mesh (TargetFrame::fine). The photo's own static detail is in its
  // texture already, so only the motion is added as geometry.
  bool wrinkles = false;
  // The new face at the target face's size (size_match.hpp): a photo does not
  // fix a face's absolute size. Self-swap (`eval swap --self`,
  // address_720p_a) median / mean 6.0 / 9.6 -> 5.0 / 7.6 grey levels.
  bool match_target_size = true;
  // Complete the photo's texture from its mirror image where the other side
  // of the face was seen more squarely (complete_from_mirror), keeping this
  // side's colour at this low-pass scale (texels). Self-swap (`eval swap
  // --self`) median / mean 4.675 / 6.65 -> 4.325 / 6.47 on address_720p_a
  // (its first frame shows the head turned), 6.675 / 10.10 -> 6.675 / 9.98 on
  // _b; without the colour ratio 4.675 / 6.51 and 7.03 / 10.30. Off for a
  // face that is not symmetric (`swap --no-mirror`).
  bool mirror_source = true;
  double mirror_low_pass_texels = 24.0;
  // Tint the new face with the target light's colour in each frame against
  // the appearance frames' (light_colour.hpp: the SH lighting is grey).
  // Self-swap (`eval swap --self`) median / mean 4.325 / 6.475 -> 4.325 /
  // 6.422 on address_720p_a, 6.675 / 9.979 -> 6.675 / 9.884 on _b.
  bool follow_light_colour = true;
  // Scale the new face by the shading pattern the target's SH lighting
  // leaves unexplained, low-pass at this Gaussian sigma on the face in mm
  // (residual_shading.hpp); 0: off. Self-swap (`eval swap --self`) median /
  // mean at 10 / 15 / 20 / 30 mm: 3.675 / 5.436, 4.025 / 5.661, 4.025 /
  // 5.748, 4.025 / 5.865 on address_720p_a (off: 4.325 / 6.070), and 5.325 /
  // 8.241, 5.675 / 8.651, 5.675 / 8.881, 6.025 / 9.126 on _b (off: 6.325 /
  // 9.474). Finer scores better and copies more of the target's own look
  // (its lips, its folds, tracking errors), which a real swap shows as a
  // ghost: 20 mm, the width of a broad shadow, is the default.
  float residual_shading_mm = 20.0f;
  // Carry the target's own change of appearance since its appearance
  // frames (folds, creases, the shadows that come and go with its
  // expression) onto the new face as a fine-scale gain
  // (expression_ratio.hpp), gated off at the target's own texture edges.
  // Self-swap (`eval swap --self`) median / mean on address_720p_a 4.0 /
  // 5.75 -> 2.67 / 4.19, on _b 5.67 / 8.88 -> 4.67 / 7.13.
  bool expression_ratio = true;
  // The photo's detail between the noise scale (noise_sigma) and this
  // fraction of the texture's width (16 texels of 1024, about 3 mm of face)
  // is scaled by photo_detail_gain (scale_detail): there the photo's texture
  // holds its own folds and shadows, which the coarse shading does not
  // remove and which land in the wrong place as the target's expression
  // changes. The cost: as much of the photo's albedo detail at that scale.
  // Self-swap (`eval swap --self`) median / mean with gains 1 / 0.8 / 0.7 /
  // 0.6: 4.325 / 6.416, 4.325 / 6.255, 4.325 / 6.210, 4.325 / 6.222
  // (address_720p_a) and 6.325 / 9.709, 6.325 / 9.567, 6.325 / 9.528, 6.325
  // / 9.539 (_b); at 32 texels (gain 0.7) 4.675 / 6.346 and 6.675 / 9.682.
  float photo_detail_gain = 0.7f;
  double photo_detail_fraction = 16.0 / 1024.0;
  // Leave what covers the target's face (a microphone, a cup, hair) in
  // front of the new face (occlusion_mask.hpp); off: the new face is laid
  // over it, as in the paper (`swap --no-occlusion`).
  bool keep_occluders = true;
  // With it, also what moves across the target's face other than the face
  // (a hand of the skin's own colour: moving_cover.hpp), at 7 ms a frame at
  // 720p, made beside the swap of the frame before by a stream
  // (frame_preparation.hpp) (`swap --no-moving-covers`: off).
  bool moving_covers = true;
  // Narrow the photo's range of skin hues to the target's (chroma_spread.hpp)
  // before the albedo adaptation: a graded, desaturated video shows less
  // colour in its faces than a photo (`swap --no-grade-match`: off).
  bool match_grade = true;
};

// The source portrait, reconstructed.
struct SourceFace {
  Eigen::VectorXf identity;    // alpha^S
  Eigen::VectorXf expression;  // beta^S
  Positions camera_points;     // face region in the photo's camera space
  PinholeCamera camera;
  ShCoeffs lighting;
};

// One tracked target frame.
class MeshHierarchy;

struct TargetFrame {
  Eigen::VectorXf identity;    // alpha^T
  Eigen::VectorXf expression;  // beta^T_t
  HeadPose pose;
  PinholeCamera camera;
  ShCoeffs lighting;
  // Whether `lighting` was estimated against the target's final albedo (the
  // refiner's albedo is fixed after its first frames; until then the
  // lighting estimates shift with it). The appearance gathered under
  // provisional lighting is used, then gathered again once it is final.
  bool lighting_final = true;
  // The frame's number in the target; where it does not follow the last
  // swapped frame's (a frame without a face between), what moves across
  // the face is looked for afresh (moving_cover.hpp). -1: unknown, taken
  // to follow.
  int index = -1;
  // This frame's preparation (frame_preparation.hpp), made beforehand on
  // another thread by make_preparation()'s; null: the swap makes it.
  const PreparedFrame* prepared = nullptr;
  // The target's face region in camera space (FaceModel::evaluate of
  // `identity` and `expression` over regions::kFace, under `pose`), where
  // the caller has it already (a stream's refinement stage evaluates it
  // for the frame); null: the swap evaluates it.
  const Positions* points = nullptr;
  // With SwapOptions::wrinkles: the refined face at the hierarchy's finest
  // level (camera space) and the hierarchy it lives on.
  Positions fine;
  const MeshHierarchy* hierarchy = nullptr;
};

struct SwapTimings {
  double appearance_ms = 0;     // texture of the target frame and harmonisation (first frames only)
  double render_ms = 0;         // both meshes, the target light's colour and residual shading, the render
  double warp_ms = 0;           // background warp
  double blend_ms = 0;          // alpha blending
  double wrinkle_ms = 0;        // coating transfer and its shading (with SwapOptions::wrinkles)
  double wrinkle_setup_ms = 0;  // the transfer's factorisation, once a shot (not in wrinkle_ms)
  double ratio_ms = 0;          // the target's unshading and change (with SwapOptions::expression_ratio)
  double occlusion_ms = 0;      // what covers the target face (with SwapOptions::keep_occluders)
  int flow_frames = 0;          // frames whose moving covers ran their optical flow (colour_change.hpp)
};

struct SwappedFrame {
  cv::Mat image;
  cv::Rect window;  // where the frame changed
  cv::Mat alpha;    // CV_32F, window-sized: the new face's share of each pixel
  // The share of the new face (of its alpha, summed) left out where
  // something covers the target's face (SwapOptions::keep_occluders).
  double covered = 0;
};

class FaceSwapper {
 public:
  FaceSwapper(const FaceModel& model, const cv::Mat& photo, SourceFace source, SwapOptions options = {});
  ~FaceSwapper();
  FaceSwapper(FaceSwapper&&) noexcept;
  FaceSwapper& operator=(FaceSwapper&&) noexcept;

  SwappedFrame swap(const cv::Mat& frame, const TargetFrame& target, SwapTimings* timings = nullptr);

  // The harmonised albedo texture (BGR 8-bit, the ICT UV layout of
  // bake_uv_texture), once a target frame has been seen.
  cv::Mat harmonised_texture() const;

  // How the source's model-space shape is placed at the target face's size
  // (SwapOptions::match_target_size), once a target frame has been seen;
  // none with the option off.
  std::optional<SizeMatch> size_match() const;

  // A preparation of target frames like the one the swapper makes for
  // itself (TargetFrame::prepared), for another thread; null where the
  // swapper needs none (SwapOptions::keep_occluders off).
  std::unique_ptr<FramePreparation> make_preparation() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
