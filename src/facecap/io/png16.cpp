#include "facecap/io/png16.hpp"

#include <algorithm>
#include <cstdint>
#include <string_view>

#include <png.h>
#include <zlib.h>
#include <opencv2/imgproc.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace {

void put_u32(std::vector<unsigned char>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

// A chunk: length, type, data, and the CRC of type and data.
void put_chunk(std::vector<unsigned char>& out, std::string_view type, const unsigned char* data, size_t size) {
  put_u32(out, uint32_t(size));
  const size_t start = out.size();
  out.insert(out.end(), type.begin(), type.end());
  out.insert(out.end(), data, data + size);
  put_u32(out, uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

// zlib's deflate of PNG's rows, one row at a time, into the IDAT data.
class RowDeflater {
 public:
  RowDeflater() {
    if (deflateInit2(&z_, 1, Z_DEFLATED, 15, 8, Z_RLE) != Z_OK)
      throw Error("cannot encode a PNG: zlib failed to start");
  }
  ~RowDeflater() { deflateEnd(&z_); }
  RowDeflater(const RowDeflater&) = delete;
  RowDeflater& operator=(const RowDeflater&) = delete;

  void add(const unsigned char* row, size_t bytes) { run(row, bytes, Z_NO_FLUSH); }
  std::vector<unsigned char> finish() {
    run(nullptr, 0, Z_FINISH);
    return std::move(out_);
  }

 private:
  void run(const unsigned char* data, size_t bytes, int flush) {
    z_.next_in = const_cast<unsigned char*>(data);
    z_.avail_in = uInt(bytes);
    int status = Z_OK;
    do {
      unsigned char buffer[1 << 16];
      z_.next_out = buffer;
      z_.avail_out = sizeof(buffer);
      status = deflate(&z_, flush);
      if (status == Z_STREAM_ERROR) throw Error("cannot encode a PNG: zlib failed");
      out_.insert(out_.end(), buffer, buffer + (sizeof(buffer) - z_.avail_out));
    } while (z_.avail_out == 0 || (flush == Z_FINISH && status != Z_STREAM_END));
  }

  z_stream z_{};
  std::vector<unsigned char> out_;
};

}  // namespace

std::vector<unsigned char> encode_png16(const cv::Mat& image) {
  const int channels = image.channels();
  if (image.empty() || image.depth() != CV_16U || (channels != 1 && channels != 3 && channels != 4))
    throw Error("cannot encode a 16-bit PNG from this image: it needs 16 bits and 1, 3 or 4 channels");
  const int width = image.cols, height = image.rows;
  // Each row as PNG stores it: a filter byte, then each sample big endian in
  // PNG's channel order (grey, or R, G, B and A where OpenCV holds B, G, R
  // and A). A row with a value is Sub-filtered (filter 1: each byte less the
  // one a pixel before it), which leaves zeros where the row is empty (a
  // pass outside the face): only the span from its first pixel with a value
  // to the one after its last is computed. An empty row is zeros,
  // unfiltered. The rows are deflated one by one, so that no buffer of the
  // whole image is made (at 1280x720 RGBA, 7.4 MB of fresh pages a frame).
  const size_t pixel_bytes = 2 * size_t(channels), stride = 1 + pixel_bytes * size_t(width);
  std::vector<unsigned char> row(stride, 0);
  std::vector<uint16_t> swapped(size_t(channels) * (size_t(width) + 1));  // a row's span, big endian in memory
  const auto* big_endian = reinterpret_cast<const unsigned char*>(swapped.data());
  const int order[4] = {channels >= 3 ? 2 : 0, 1, 0, 3};  // grey: only order[0], 0
  const auto empty = [channels](const uint16_t* pixel) {
    for (int c = 0; c < channels; ++c)
      if (pixel[c] != 0) return false;
    return true;
  };
  RowDeflater deflater;
  size_t dirty = 0;  // the bytes of `row` the last row set: [0, dirty)
  for (int y = 0; y < height; ++y) {
    std::fill_n(row.begin(), std::ptrdiff_t(dirty), 0);
    dirty = 0;
    const uint16_t* in = image.ptr<uint16_t>(y);
    int first = 0, last = width - 1;
    while (first < width && empty(in + size_t(first) * channels)) ++first;
    if (first < width) {
      while (empty(in + size_t(last) * channels)) --last;
      const int end = std::min(width, last + 2);  // the pixel after the last, whose Sub value is 0 less it
      uint16_t* samples = swapped.data();
      for (int x = first; x <= last; ++x) {
        const uint16_t* pixel = in + size_t(x) * channels;
        uint16_t* to = samples + size_t(x - first) * channels;
        for (int c = 0; c < channels; ++c) to[c] = __builtin_bswap16(pixel[order[c]]);
      }
      if (end > last + 1) std::fill_n(samples + size_t(last + 1 - first) * channels, channels, uint16_t(0));
      row[0] = 1;  // Sub
      unsigned char* out = row.data() + 1 + size_t(first) * pixel_bytes;
      const size_t span = size_t(end - first) * pixel_bytes;
      std::copy_n(big_endian, pixel_bytes, out);  // the pixel before the first is 0
      for (size_t i = pixel_bytes; i < span; ++i)
        out[i] = static_cast<unsigned char>(big_endian[i] - big_endian[i - pixel_bytes]);
      dirty = 1 + size_t(first) * pixel_bytes + span;
    }
    deflater.add(row.data(), row.size());
  }
  const std::vector<unsigned char> deflated = deflater.finish();

  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  png.reserve(deflated.size() + 64);
  std::vector<unsigned char> header;
  put_u32(header, uint32_t(width));
  put_u32(header, uint32_t(height));
  const unsigned char colour_type = channels == 1 ? 0 : channels == 3 ? 2 : 6;  // grey, RGB, RGBA
  header.insert(header.end(), {16, colour_type, 0, 0, 0});  // 16 bits, deflate, adaptive filters, no interlace
  put_chunk(png, "IHDR", header.data(), header.size());
  std::vector<unsigned char> gamma;
  put_u32(gamma, 100000);  // 1.0: linear
  put_chunk(png, "gAMA", gamma.data(), gamma.size());
  put_chunk(png, "IDAT", deflated.data(), deflated.size());
  put_chunk(png, "IEND", nullptr, 0);
  return png;
}

cv::Mat read_png16(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  if (!bytes) return {};
  png_image header{};
  header.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&header, bytes->data(), bytes->size())) return {};
  const bool colour = (header.format & PNG_FORMAT_FLAG_COLOR) != 0,
             alpha = (header.format & PNG_FORMAT_FLAG_ALPHA) != 0;
  const int channels = colour ? (alpha ? 4 : 3) : (alpha ? 4 : 1);
  header.format = channels == 1   ? PNG_FORMAT_LINEAR_Y
                  : channels == 3 ? PNG_FORMAT_LINEAR_RGB
                                  : PNG_FORMAT_LINEAR_RGB_ALPHA;
  cv::Mat image(int(header.height), int(header.width), CV_16UC(channels));
  if (!png_image_finish_read(&header, nullptr, image.data, png_int_32(image.step / image.elemSize1()), nullptr)) {
    png_image_free(&header);
    return {};
  }
  if (channels == 3) cv::cvtColor(image, image, cv::COLOR_RGB2BGR);
  if (channels == 4) cv::cvtColor(image, image, cv::COLOR_RGBA2BGRA);
  return image;
}

}  // namespace facecap
