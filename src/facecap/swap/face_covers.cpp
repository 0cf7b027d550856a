#include "facecap/swap/face_covers.hpp"

#include "facecap/model/regions.hpp"
#include "facecap/render/uv_raster.hpp"

namespace facecap {

double mean_face_mm_per_uv(const FaceModel& model, const TriangleMesh& skin) {
  const Eigen::VectorXf none;
  return millimetres_per_uv(skin,
                            model.with_expression(model.identity_shape(none, regions::kFace), none, regions::kFace));
}

FaceCovers::FaceCovers(const FaceModel& model, const TriangleMesh& skin, CoverOptions options, double mm_per_uv)
    : model_(&model), options_(options), skin_(&skin), occlusion_(skin, mm_per_uv) {}

std::unique_ptr<FramePreparation> FaceCovers::new_preparation() const {
  return std::make_unique<FramePreparation>(*model_, *skin_, occlusion_.grid(), options_.moving_covers);
}

cv::Mat FaceCovers::covered(const PreparedFrame& prepared, bool lighting_final) {
  if (!lighting_final) restart();
  if (references_ < options_.reference_frames) {
    occlusion_.add_reference(prepared.seen);
    ++references_;
  }
  return occlusion_.covered(prepared.seen, prepared.moving);
}

void FaceCovers::restart() {
  occlusion_.clear_reference();
  references_ = 0;
}

}  // namespace facecap
