#include "facecap/pipeline/photo_face_texture.hpp"

#include "facecap/pipeline/swap_job.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/skin_texture.hpp"

namespace facecap {

cv::Mat face_texture_from_photo(const FaceModel& model, const std::string& photo, int size, bool quiet) {
  const SourceReconstruction source = reconstruct_source(model, photo, quiet, 1);
  const SourceFace& face = source.face;
  const TriangleMesh skin = skin_mesh(model);
  const FaceTexture texture = unshade_photo(model, source.photo, face.camera_points, face.camera, face.lighting, skin,
                                            rasterize_uv(skin, size), SwapOptions{}.mirror_low_pass_texels);
  const cv::Mat filled = fill_unseen(texture.albedo, texture.weight);
  return cv::min(cv::max(filled, 0.0f), 1.0f);
}

}  // namespace facecap
