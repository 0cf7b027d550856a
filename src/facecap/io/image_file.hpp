#pragma once
// Still images read and written without OpenCV's imgcodecs, whose own
// dependencies (GDAL, GDCM, Poppler, HDF5 and about a hundred more libraries)
// cost every facecap process about 0.1 s of dynamic loading before main().
// JPEG goes through libjpeg-turbo with the settings cv::imread uses (so the
// same pixels), its EXIF orientation applied as cv::imread applies it; PNG is
// written with libpng; PNG, BMP, TIFF, WebP and PNM are read with libavcodec.
#include <filesystem>
#include <span>
#include <vector>

#include <opencv2/core.hpp>

namespace facecap {

// 8-bit BGR, as cv::imread(path, cv::IMREAD_COLOR) gives; empty when the
// file cannot be read or is not an image in a format named above.
cv::Mat read_image(const std::filesystem::path& path);
cv::Mat decode_image(std::span<const unsigned char> bytes);

// An image of 1, 3 (BGR) or 4 (BGRA) channels, 8 bits a channel, or 16
// (data: png16.hpp); throws facecap::Error for any other.
std::vector<unsigned char> encode_png(const cv::Mat& image);
// An 8-bit image of 1 or 3 (BGR) channels.
std::vector<unsigned char> encode_jpeg(const cv::Mat& image, int quality = 95);

// Encoded by the name's extension (.png, .jpg, .jpeg) and written whole or
// not at all; throws facecap::Error naming the file.
void write_image(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace facecap
