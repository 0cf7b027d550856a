#pragma once
// The part of a target frame's swap that needs nothing the swapper learns
// from the target's appearance frames: the face unshaded onto the
// occlusion mask's grid (what the colour test and the expression ratio
// read) and what moves across it (MovingCover). A swap does it on another
// thread, beside the swap of the frame before (FaceSwapStream), or in the
// swap itself where it is given none.
#include <memory>
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/swap/colour_change.hpp"
#include "facecap/swap/face_texture.hpp"
#include "facecap/swap/moving_cover.hpp"

namespace facecap {

struct PreparedFrame {
  FaceTexture seen;              // the frame unshaded onto the grid, nothing dropped (OcclusionMask::unshade)
  cv::Mat moving;                // MovingCover's evidence on the grid (empty: moving covers off)
  bool motion_measured = false;  // MovingCover ran its optical flow on this frame (MovingCover::measured_motion)
};

class FramePreparation {
 public:
  // `skin` with UVs and `grid` the occlusion mask's; moving covers only
  // where `moving_covers`.
  FramePreparation(const FaceModel& model, const TriangleMesh& skin, const MillimetreGrid& grid, bool moving_covers);
  ~FramePreparation();
  FramePreparation(FramePreparation&&) noexcept;
  FramePreparation& operator=(FramePreparation&&) noexcept;

  // `points`: the target's face region in camera space; `frame_index` as
  // MovingCover::update's.
  PreparedFrame prepare(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera,
                        const ShCoeffs& lighting, int frame_index);

  // Forget the last frame (a shot cut).
  void reset();

 private:
  const FaceModel* model_;
  TriangleMesh skin_;
  UvTexelMap map_;
  std::unique_ptr<MovingCover> moving_;  // null: moving covers off
  ColourChange colour_change_;           // whether the moving covers need their flow
};

}  // namespace facecap
