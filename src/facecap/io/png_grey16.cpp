#include "facecap/io/png_grey16.hpp"

#include <array>
#include <cstdint>
#include <string_view>

#include <png.h>
#include <zlib.h>

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

}  // namespace

std::vector<unsigned char> encode_png_grey16(const cv::Mat& image) {
  if (image.empty() || image.type() != CV_16UC1) throw Error("cannot encode a 16-bit grey PNG from this image");
  const int width = image.cols, height = image.rows;
  // The rows as PNG stores them: a filter byte (1, Sub), then each sample big
  // endian, less the byte two places before it (the previous sample's).
  const size_t stride = 1 + 2 * size_t(width);
  std::vector<unsigned char> rows(stride * size_t(height));
  for (int y = 0; y < height; ++y) {
    const uint16_t* in = image.ptr<uint16_t>(y);
    unsigned char* out = rows.data() + stride * size_t(y);
    out[0] = 1;
    uint16_t previous = 0;
    for (int x = 0; x < width; ++x) {
      const uint16_t v = in[x];
      out[1 + 2 * x] = static_cast<unsigned char>((v >> 8) - (previous >> 8));
      out[2 + 2 * x] = static_cast<unsigned char>((v & 0xff) - (previous & 0xff));
      previous = v;
    }
  }
  z_stream z{};
  if (deflateInit2(&z, 1, Z_DEFLATED, 15, 8, Z_RLE) != Z_OK) throw Error("cannot encode a PNG: zlib failed to start");
  std::vector<unsigned char> deflated(deflateBound(&z, uLong(rows.size())));
  z.next_in = rows.data();
  z.avail_in = uInt(rows.size());
  z.next_out = deflated.data();
  z.avail_out = uInt(deflated.size());
  const int status = deflate(&z, Z_FINISH);
  deflated.resize(z.total_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw Error("cannot encode a PNG: zlib failed");

  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> header;
  put_u32(header, uint32_t(width));
  put_u32(header, uint32_t(height));
  header.insert(header.end(), {16, 0, 0, 0, 0});  // 16 bits, grey, deflate, adaptive filters, no interlace
  put_chunk(png, "IHDR", header.data(), header.size());
  std::vector<unsigned char> gamma;
  put_u32(gamma, 100000);  // 1.0: linear
  put_chunk(png, "gAMA", gamma.data(), gamma.size());
  put_chunk(png, "IDAT", deflated.data(), deflated.size());
  put_chunk(png, "IEND", nullptr, 0);
  return png;
}

cv::Mat read_png_grey16(const std::filesystem::path& path) {
  const auto bytes = read_binary_file(path);
  if (!bytes) return {};
  png_image header{};
  header.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&header, bytes->data(), bytes->size())) return {};
  header.format = PNG_FORMAT_LINEAR_Y;
  cv::Mat image(int(header.height), int(header.width), CV_16UC1);
  if (!png_image_finish_read(&header, nullptr, image.data, png_int_32(image.step / image.elemSize1()), nullptr)) {
    png_image_free(&header);
    return {};
  }
  return image;
}

}  // namespace facecap
