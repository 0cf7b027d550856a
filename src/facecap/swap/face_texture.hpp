#pragma once
// A face's appearance without its lighting, in UV space: every texel of the
// face's UV layout takes the image colour at its surface point divided by the
// SH shading there (I = l . SH(n) * albedo, eq. 6.4/6.7), weighted by how
// squarely the camera saw it (0 where it did not). Texture resolution, not
// the coarse mesh's, carries the skin detail the paper keeps per vertex of
// its subdivided mesh.
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/uv_raster.hpp"

namespace facecap {

struct FaceTexture {
  cv::Mat albedo;  // CV_32FC3, BGR, size x size
  cv::Mat weight;  // CV_32F, 0 where the surface point was not seen

  bool empty() const { return albedo.empty(); }
};

// `camera_points`: the face's vertices in camera space for `image`;
// `triangles`: the mesh the texel map was built from. Surface points that
// land inside an `excluded` image polygon (the open mouth, the eyes: what
// the skin mesh does not model) count as unseen.
FaceTexture unshade_face(const cv::Mat& image, const Positions& camera_points, const std::vector<Triangle>& triangles,
                         const PinholeCamera& camera, const ShCoeffs& lighting, const UvTexelMap& map,
                         const std::vector<std::vector<cv::Point>>& excluded = {});

// Drops (zero weight) the texels whose colour is far from the face's median
// skin colour in chromaticity or brightness: a collar, hair or a hand the
// coarse mesh's outline covers. Returns how many texels it dropped.
int drop_non_skin(FaceTexture& texture, float max_chroma = 0.05f, float max_log_brightness = 0.9f);

// Completes a photo's texture from its mirror image. ICT's face and its UV
// layout are left-right symmetric (the surface point at (u, v) mirrors to
// (1 - u, v)), and a photo of a turned head sees its far cheek obliquely or
// not at all. Where the mirror texel was seen more squarely (a higher
// weight), it is blended in by the difference of the weights, carrying its
// detail but not its colour: it is scaled by the ratio of this side's
// low-pass colour to the mirror side's (Gaussian, `low_pass_texels`;
// weighted by what each side saw), as the two sides differ by what the
// de-lighting left. The texel's weight becomes the mirror's.
void complete_from_mirror(FaceTexture& texture, double low_pass_texels);

// Scales the detail of `albedo` finer than a Gaussian of `sigma` texels by
// `gain`: blur + gain (albedo - blur). A photo's texture below that scale is
// partly its own shading (the folds and shadows of its expression and pose,
// which the coarse shading model does not remove); rendered on another
// expression it lands in the wrong place.
cv::Mat scale_detail(const cv::Mat& albedo, double sigma, float gain);

// Adds `one` to a weighted running sum (albedo * weight and weight).
void accumulate(FaceTexture& sum, const FaceTexture& one);
// The weighted mean of an accumulated sum.
FaceTexture weighted_mean(const FaceTexture& sum);

// Fills the texels with zero weight (where the camera never saw the face)
// from their seen neighbourhood, coarse to fine (push-pull).
cv::Mat fill_unseen(const cv::Mat& albedo, const cv::Mat& weight);

}  // namespace facecap
