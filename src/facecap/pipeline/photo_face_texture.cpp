#include "facecap/pipeline/photo_face_texture.hpp"

#include "facecap/pipeline/refine_eval.hpp"
#include "facecap/pipeline/swap_job.hpp"
#include "facecap/render/uv_raster.hpp"
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

cv::Mat face_texture_of_frame(const FaceModel& model, const cv::Mat& image, const Positions& points,
                              const PinholeCamera& camera, const ShCoeffs& lighting, int size) {
  const TriangleMesh skin = skin_mesh(model);
  const FaceTexture texture = unshade_photo(model, image, points, camera, lighting, skin, rasterize_uv(skin, size),
                                            SwapOptions{}.mirror_low_pass_texels);
  const cv::Mat filled = fill_unseen(texture.albedo, texture.weight);
  return cv::min(cv::max(filled, 0.0f), 1.0f);
}

}  // namespace facecap
