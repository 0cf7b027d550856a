#pragma once
// 16-bit grey PNGs: data such as a detail map (pipeline/detail_maps.hpp), not
// a picture. Written with zlib directly, each row Sub-filtered and deflated
// with run-length matching: for a smooth 16-bit field about three times as
// fast as libpng's simplified writer (zlib's default strategy, no filter),
// and 20 % smaller.
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace facecap {

// image: CV_16UC1. The file is marked linear (gAMA 1.0): its values are data.
// Throws facecap::Error for any other image.
std::vector<unsigned char> encode_png_grey16(const cv::Mat& image);

// A PNG as 16-bit grey (CV_16UC1): a 16-bit grey one as written, any other
// converted by libpng; empty when the file cannot be read as a PNG.
cv::Mat read_png_grey16(const std::filesystem::path& path);

}  // namespace facecap
