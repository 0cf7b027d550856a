#pragma once
// 16-bit PNGs: data such as a detail map (pipeline/detail_maps.hpp) or a UV
// pass (render/uv_pass.hpp), not a picture. Written with zlib directly, each
// row Sub-filtered and deflated with run-length matching: a detail map of
// address_720p_a (1024 x 1024) in 12.8 ms and 298 KB, against 35.1 ms and
// 373 KB from libpng's simplified writer (zlib's default strategy, no
// filter).
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace facecap {

// image: CV_16UC1 (grey), CV_16UC3 (BGR) or CV_16UC4 (BGRA), OpenCV's channel
// order, stored as PNG's grey, RGB or RGBA. The file is marked linear (gAMA
// 1.0): its values are data. Throws facecap::Error for any other image.
std::vector<unsigned char> encode_png16(const cv::Mat& image);

// A PNG as 16 bits a channel with the file's channels (CV_16UC1, CV_16UC3 as
// BGR or CV_16UC4 as BGRA; a palette or grey-alpha file as BGR(A)): a 16-bit
// file as written, any other converted by libpng (with alpha, colours
// premultiplied by it, which leaves a pixel of alpha 0 or 65535 as it was);
// empty when the file cannot be read as a PNG.
cv::Mat read_png16(const std::filesystem::path& path);

}  // namespace facecap
