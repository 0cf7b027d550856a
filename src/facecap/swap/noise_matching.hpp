#pragma once
// Noise matching, eq. 6.4-6.5: the source face's fine residual (its image
// colour minus the smooth shaded albedo) is remapped so that its histogram
// matches the target face's, so that the swapped face carries the grain,
// blur and compression of the target footage rather than of the photo.
#include <opencv2/core.hpp>

namespace facecap {

// Per channel, the monotone map (256 bins over [lo, hi]) that sends the
// distribution of `source` over `source_mask` to that of `target` over
// `target_mask`; returns the remapped source (CV_32FC3, same size).
cv::Mat match_histograms(const cv::Mat& source, const cv::Mat& source_mask, const cv::Mat& target,
                         const cv::Mat& target_mask, float lo, float hi, int bins = 256);

// The fine residual of an albedo texture: itself minus its Gaussian blur
// (sigma in texels; wide_blur.hpp).
cv::Mat fine_residual(const cv::Mat& albedo, double sigma);

}  // namespace facecap
