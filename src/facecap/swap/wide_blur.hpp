#pragma once
// A Gaussian blur for the wide low-passes of the swap's textures (sigmas of
// tens of texels on a 1024 texture: an exact kernel of 8 sigma is a few
// hundred taps a texel).
#include <opencv2/core.hpp>

namespace facecap {

// A Gaussian blur of `sigma` texels with `border` (cv::BorderTypes). From a
// sigma of 8 on it runs on a grid `sigma / 4` times coarser (box-averaged
// down, blurred, bilinear back up): within a few thousandths of the exact
// blur of a smooth image, in a twentieth of the time at sigma 24.
cv::Mat wide_blur(const cv::Mat& image, double sigma, int border = cv::BORDER_REFLECT_101);

}  // namespace facecap
