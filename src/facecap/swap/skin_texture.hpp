#pragma once
// The skin a swap re-renders, and a photo's face unshaded onto it: the
// surface (the narrow face of FACTS.md, with its UVs), the image polygons
// of what it does not model (eyes, mouth interior), and the photo's
// appearance without its lighting in the skin's UV layout (eq. 6.4).
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/face_texture.hpp"

namespace facecap {

// The skin of the face region (the narrow face of FACTS.md) with its UVs.
TriangleMesh skin_mesh(const FaceModel& model);

// The image polygons of what the skin mesh does not model: the eyes
// (landmarks 36-41, 42-47) and the mouth interior (inner lips 60-67).
// `points`: the face region in camera space.
std::vector<std::vector<cv::Point>> feature_holes(const FaceModel& model, const Positions& points,
                                                  const PinholeCamera& camera);

// A photo's face in the skin's UV layout (`map`, rasterised from `skin`):
// unshaded by its SH `lighting` with the eyes and mouth left out, texels
// off the skin's colour dropped (drop_non_skin), and, where
// `mirror_low_pass_texels` > 0, the side the photo sees obliquely completed
// from its mirror image (complete_from_mirror). `camera_points`: the fitted
// face region in the photo's camera space.
FaceTexture unshade_photo(const FaceModel& model, const cv::Mat& photo, const Positions& camera_points,
                          const PinholeCamera& camera, const ShCoeffs& lighting, const TriangleMesh& skin,
                          const UvTexelMap& map, double mirror_low_pass_texels);

}  // namespace facecap
