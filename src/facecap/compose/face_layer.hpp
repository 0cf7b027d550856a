#pragma once
// A layer to composite over a frame: a window of the frame holding new
// colour where its mask is set and the frame's own colour elsewhere, so that
// multi-band blending (which spreads each band over its neighbourhood)
// mixes the new face with the real surroundings, never with black.
#include <opencv2/core.hpp>

namespace facecap {

struct FaceLayer {
  cv::Rect box;    // the window in the frame
  cv::Mat colour;  // BGR 8-bit, box-sized
  cv::Mat mask;    // 8-bit, box-sized, 255 where the layer replaces the frame
  // 8-bit, box-sized: the new face's share of each pixel, for a matte, where
  // it is not layer_blend_mask() (a swap's layer, whose mask is every pixel
  // it changed, its warped background too); empty: layer_blend_mask().
  cv::Mat share;
};

// A window around `content` (grown by `margin`, clipped to the frame) holding
// the frame's pixels and an empty mask.
FaceLayer make_layer(const cv::Mat& frame, cv::Rect content, int margin);

// The mask composite_layer() blends the layer with (8-bit, box-sized): the
// layer's eroded by `inset` pixels and feathered by `feather` pixels; the
// pyramid then spreads each band over its own scale.
cv::Mat layer_blend_mask(const FaceLayer& layer, int inset = 2, double feather = 3.0);

// The new face's share of each pixel of the layer's box (8-bit): `share`,
// or layer_blend_mask() where it has none.
cv::Mat layer_share(const FaceLayer& layer);

// Blends the layer into the frame in place: with layer_blend_mask() and a
// Laplacian pyramid of `levels`.
void composite_layer(cv::Mat& frame, const FaceLayer& layer, int inset = 2, double feather = 3.0, int levels = 5);

}  // namespace facecap
