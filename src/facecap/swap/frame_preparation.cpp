#include "facecap/swap/frame_preparation.hpp"

#include "facecap/swap/skin_texture.hpp"

namespace facecap {

FramePreparation::FramePreparation(const FaceModel& model, const TriangleMesh& skin, const MillimetreGrid& grid,
                                   bool moving_covers)
    : model_(&model), skin_(skin), map_(grid.map), colour_change_(grid.texels_per_mm) {
  if (moving_covers) moving_ = std::make_unique<MovingCover>(skin, grid);
}

FramePreparation::~FramePreparation() = default;
FramePreparation::FramePreparation(FramePreparation&&) noexcept = default;
FramePreparation& FramePreparation::operator=(FramePreparation&&) noexcept = default;

PreparedFrame FramePreparation::prepare(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera,
                                        const ShCoeffs& lighting, int frame_index) {
  PreparedFrame out;
  out.seen =
      unshade_face(frame, points, skin_.triangles, camera, lighting, map_, feature_holes(*model_, points, camera));
  if (moving_)
    out.moving = moving_->update(frame, points, camera, out.seen.weight, frame_index,
                                 colour_change_.changed(out.seen, frame_index));
  out.motion_measured = moving_ && moving_->measured_motion();
  return out;
}

void FramePreparation::reset() {
  if (moving_) moving_->reset();
  colour_change_.reset();
}

}  // namespace facecap
