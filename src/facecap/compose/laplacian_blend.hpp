#pragma once
// Multi-band blending (Burt and Adelson's Laplacian pyramids, §5.3.3): a
// layer is blended over a base with a soft mask, each frequency band with a
// mask blurred to its scale, so seams vanish without ghosting detail.
#include <opencv2/core.hpp>

namespace facecap {

// base, layer: BGR 8-bit of one size; mask: 8-bit of that size (255 = layer).
// The layer must equal the base wherever it has nothing new to say: its
// coarse bands spread over the whole neighbourhood of the mask.
cv::Mat laplacian_blend(const cv::Mat& base, const cv::Mat& layer, const cv::Mat& mask, int levels = 5);

// A mask with a soft edge: eroded by `inset` pixels, then blurred by `feather` pixels.
cv::Mat feather_mask(const cv::Mat& mask, int inset, double feather);

}  // namespace facecap
