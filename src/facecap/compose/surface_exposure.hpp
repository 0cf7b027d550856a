#pragma once
// How much of a re-rendered surface the source frame shows. Re-rendering
// from the frame (face_reshading.hpp) takes each new pixel's colour from
// the same surface point in the frame; where the new surface unfolds what
// the old one had folded away or turned edge-on (a closing lid, which ICT
// folds under the brow while the eye is open), a few pixels of the frame
// are stretched over many: the lid rim's highlight became a pale blob over
// the whole closed lid. There the frame holds no texture to take.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"

namespace facecap {

// Per vertex, the projected area of its triangles on the old surface over
// that on the new, both through `camera`: 1 where the surface only moved,
// towards 0 where the new surface shows what the frame saw edge-on or not
// at all (a triangle turned over between them counts as unseen), above 1
// where it is squeezed. 1 for a vertex without triangles of any area.
std::vector<float> vertex_exposure(const Positions& old_points, const Positions& new_points,
                                   const std::vector<Triangle>& triangles, const PinholeCamera& camera);

// How far a pixel of exposure `exposure` can take the frame's colour: 0 up
// to kUnseenExposure, 1 from kSeenExposure, smooth between. On a closed lid
// of address_720p_a (`--units AU45=5`), 0.4 left the rim's highlight, which
// the lid stretches about 3 times, a pale spot; at 0.8 it is gone, and
// the emotions' outputs hardly change (sadness, 100 frames: PSNR 49.6 dB
// against none).
constexpr float kUnseenExposure = 0.15f;
constexpr float kSeenExposure = 0.8f;
float exposure_trust(float exposure);

// Mixes into each pixel of `colour` (CV_8UC3) with `trust` (CV_32F, 0 to 1,
// the same size) below 1 the colour of the trusted pixels of `surface`
// (CV_8U, non-zero: the re-rendered skin, not the eyes or the background
// the layer also holds) around it, by 1 - trust: their mean under a
// Gaussian of `sigma` pixels, each weighted by its trust (a normalised
// convolution). Pixels with no such pixel within reach keep their colour.
void fill_untrusted(cv::Mat& colour, const cv::Mat& trust, const cv::Mat& surface, double sigma);

}  // namespace facecap
