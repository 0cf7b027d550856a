#pragma once
// The swap's new face drawn (eq. 6.7): the harmonised albedo texture under
// the target's SH lighting, on the swapped mesh's normals, its colour and
// shading following the target's (FaceLight), faded toward its silhouette
// (silhouette_fade.hpp).
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/texture_levels.hpp"

namespace facecap {

// What the SH shading is multiplied by, per pixel: the target light's
// colour now against its first frames' (light_colour.hpp), the shading
// pattern its SH lighting leaves unexplained (residual_shading.hpp) and the
// target's fine change of appearance (expression_ratio.hpp), each gain map
// in the texture's layout (empty: none).
struct FaceLight {
  Vec3f tint = Vec3f::Ones();
  cv::Mat residual_gains;    // CV_32FC3
  cv::Mat expression_gains;  // CV_32F or CV_32FC3
};

// The face `points` (camera space, with their vertex `normals`) on the skin
// mesh, drawn with `texture` (BGR and alpha, levels of detail) into the
// window `window` sees, `size` pixels; `frame_camera` is the whole frame's,
// which sets the texture's level of detail and the fade's width. Returns
// the colour (CV_32FC3, 0-255); `alpha` (CV_32F) receives the face's share
// of each pixel.
cv::Mat render_swapped_face(const TriangleMesh& skin, const TextureLevels& texture, const Positions& points,
                            const Positions& normals, const PinholeCamera& frame_camera, const PinholeCamera& window,
                            cv::Size size, const ShCoeffs& lighting, const FaceLight& light,
                            float silhouette_fade_start, cv::Mat& alpha);

}  // namespace facecap
