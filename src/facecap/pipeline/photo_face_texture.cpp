#include "facecap/pipeline/photo_face_texture.hpp"

#include <algorithm>

#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/swap_job.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/face_texture.hpp"
#include "facecap/swap/skin_texture.hpp"

namespace facecap {

cv::Mat face_texture_from_photo(const FaceModel& model, const std::string& photo, int size, bool quiet) {
  const SourceReconstruction source = reconstruct_source(model, photo, quiet, 1);
  const SourceFace& face = source.face;
  return face_texture_of_frame(model, source.photo, face.camera_points, face.camera, face.lighting, size);
}

ShCoeffs face_lighting_of_frame(const FaceModel& model, const cv::Mat& image, const Positions& points,
                                const PinholeCamera& camera) {
  // The frame is all there is: it fixes the albedo at once, with the fixing
  // frame's lighting/albedo rounds (4) rather than an early frame's (2).
  // Self-swap (`eval swap --self`) mean 6.100 -> 6.070 (address_720p_a),
  // 9.502 -> 9.474 (_b).
  RefineOptions options = lighting_only_refinement();
  options.albedo.frames = 1;
  Refiner refiner = make_face_refiner(model, options);
  return refiner.refine(image, points, camera).lighting;
}

namespace {

// A texture completed as a photo's: from its mirror image, then filled where unseen.
cv::Mat finished_texture(FaceTexture texture) {
  complete_from_mirror(texture, SwapOptions{}.mirror_low_pass_texels);
  const cv::Mat filled = fill_unseen(texture.albedo, texture.weight);
  return cv::min(cv::max(filled, 0.0f), 1.0f);
}

}  // namespace

cv::Mat face_texture_of_frame(const FaceModel& model, const cv::Mat& image, const Positions& points,
                              const PinholeCamera& camera, const ShCoeffs& lighting, int size) {
  const TriangleMesh skin = skin_mesh(model);
  return finished_texture(unshade_photo(model, image, points, camera, lighting, skin, rasterize_uv(skin, size), 0.0));
}

struct FaceTextureGatherer::Impl {
  Impl(const FaceModel& m, int f, int size)
      : model(m), frames(f), skin(skin_mesh(m)), map(rasterize_uv(skin, size)), lighting(new_lighting_refiner()) {}

  Refiner new_lighting_refiner() const {
    // As a photo's (face_lighting_of_frame) for one frame; over more, the
    // albedo the lighting is estimated against is fixed over up to 4.
    RefineOptions options = lighting_only_refinement();
    options.albedo.frames = std::clamp(frames, 1, options.albedo.frames);
    return make_face_refiner(model, options);
  }

  const FaceModel& model;
  int frames;
  TriangleMesh skin;
  UvTexelMap map;
  Refiner lighting;
  FaceTexture sum;
  int added = 0;
};

FaceTextureGatherer::FaceTextureGatherer(const FaceModel& model, int frames, int size)
    : impl_(std::make_unique<Impl>(model, std::max(1, frames), size)) {}
FaceTextureGatherer::~FaceTextureGatherer() = default;
FaceTextureGatherer::FaceTextureGatherer(FaceTextureGatherer&&) noexcept = default;
FaceTextureGatherer& FaceTextureGatherer::operator=(FaceTextureGatherer&&) noexcept = default;

bool FaceTextureGatherer::wants_more() const { return impl_->added < impl_->frames; }

void FaceTextureGatherer::add(const cv::Mat& image, const Positions& points, const PinholeCamera& camera) {
  Impl& m = *impl_;
  const ShCoeffs lighting = m.lighting.refine(image, points, camera).lighting;
  accumulate(m.sum, unshade_photo(m.model, image, points, camera, lighting, m.skin, m.map, 0.0));
  ++m.added;
}

bool FaceTextureGatherer::empty() const { return impl_->added == 0; }

cv::Mat FaceTextureGatherer::texture() const {
  if (empty()) return {};
  return finished_texture(weighted_mean(impl_->sum));
}

void FaceTextureGatherer::clear() {
  impl_->sum = FaceTexture();
  impl_->added = 0;
  impl_->lighting = impl_->new_lighting_refiner();
}

}  // namespace facecap
