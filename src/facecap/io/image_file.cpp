#include "facecap/io/image_file.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libswscale/swscale.h>
}
// clang-format off: jpeglib.h needs <cstdio> before it
#include <jpeglib.h>
#include <cstdio>
// clang-format on
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/png16.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// ------------------------------------------------------------------ JPEG

// libjpeg reports a fatal error by calling error_exit, whose default ends
// the process: it jumps back to the call instead. Its warnings (a truncated
// file's "premature end of data") stay silent, as the image still decodes.
struct JpegErrors {
  jpeg_error_mgr manager{};
  std::jmp_buf jump{};
};

void jump_back(j_common_ptr info) { std::longjmp(reinterpret_cast<JpegErrors*>(info->err)->jump, 1); }
void stay_silent(j_common_ptr) {}

JpegErrors* install_errors(JpegErrors& errors) {
  jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jump_back;
  errors.manager.output_message = stay_silent;
  return &errors;
}

// The EXIF orientation (1-8; 1 upright) in an APP1 segment, or 1.
int exif_orientation(const unsigned char* data, size_t size) {
  if (size < 14 || std::memcmp(data, "Exif\0\0", 6) != 0) return 1;
  const unsigned char* tiff = data + 6;
  const size_t n = size - 6;
  const bool little = tiff[0] == 'I' && tiff[1] == 'I';
  if (!little && !(tiff[0] == 'M' && tiff[1] == 'M')) return 1;
  const auto u16 = [&](size_t at) -> uint32_t {
    if (at + 2 > n) return 0;
    return little ? tiff[at] | tiff[at + 1] << 8 : tiff[at] << 8 | tiff[at + 1];
  };
  const auto u32 = [&](size_t at) -> uint32_t {
    return little ? u16(at) | u16(at + 2) << 16 : u16(at) << 16 | u16(at + 2);
  };
  const size_t ifd = u32(4);
  const uint32_t entries = u16(ifd);
  for (uint32_t i = 0; i < entries; ++i) {
    const size_t entry = ifd + 2 + 12 * size_t(i);
    if (entry + 12 > n) break;
    if (u16(entry) == 0x0112) {
      const uint32_t value = u16(entry + 8);
      return value >= 1 && value <= 8 ? int(value) : 1;
    }
  }
  return 1;
}

// As cv::imread turns an image by its EXIF orientation.
void apply_orientation(cv::Mat& image, int orientation) {
  if (orientation >= 5) cv::transpose(image, image);
  switch (orientation) {
    case 2:
    case 6:
      cv::flip(image, image, 1);
      break;
    case 3:
    case 7:
      cv::flip(image, image, -1);
      break;
    case 4:
    case 8:
      cv::flip(image, image, 0);
      break;
    default:
      break;
  }
}

// Decodes into `out` (8-bit BGR) as OpenCV's JPEG decoder does: libjpeg's
// own BGR output for 1 and 3 components, Adobe-style CMYK converted by
// OpenCV's formula. No object with a destructor lives in this frame, which
// libjpeg's errors leave by longjmp.
bool decode_jpeg(std::span<const unsigned char> bytes, cv::Mat& out, int& orientation) {
  jpeg_decompress_struct info{};
  JpegErrors errors;
  info.err = &install_errors(errors)->manager;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_save_markers(&info, JPEG_APP0 + 1, 0xffff);
  jpeg_read_header(&info, TRUE);
  orientation = 1;
  for (jpeg_saved_marker_ptr m = info.marker_list; m != nullptr; m = m->next) {
    if (m->marker == JPEG_APP0 + 1 && orientation == 1) orientation = exif_orientation(m->data, m->data_length);
  }
  const bool cmyk = info.num_components == 4;
  info.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_BGR;
  info.out_color_components = cmyk ? 4 : 3;
  jpeg_start_decompress(&info);
  out.create(int(info.output_height), int(info.output_width), CV_8UC3);
  JSAMPARRAY row =
      cmyk ? (*info.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&info), JPOOL_IMAGE, info.output_width * 4, 1)
           : nullptr;
  while (info.output_scanline < info.output_height) {
    unsigned char* bgr = out.ptr(int(info.output_scanline));
    JSAMPROW target = cmyk ? row[0] : bgr;
    jpeg_read_scanlines(&info, &target, 1);
    if (!cmyk) continue;
    for (JDIMENSION x = 0; x < info.output_width; ++x) {
      const int c = row[0][4 * x], m = row[0][4 * x + 1], y = row[0][4 * x + 2], k = row[0][4 * x + 3];
      bgr[3 * x + 2] = static_cast<unsigned char>(k - ((255 - c) * k >> 8));
      bgr[3 * x + 1] = static_cast<unsigned char>(k - ((255 - m) * k >> 8));
      bgr[3 * x] = static_cast<unsigned char>(k - ((255 - y) * k >> 8));
    }
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

// Encodes an 8-bit grey or BGR image into `*buffer` (malloc'd by libjpeg).
bool encode_jpeg_into(const cv::Mat& image, int quality, unsigned char** buffer, unsigned long* size) {
  jpeg_compress_struct info{};
  JpegErrors errors;
  info.err = &install_errors(errors)->manager;
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&info);
    return false;
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, buffer, size);
  info.image_width = JDIMENSION(image.cols);
  info.image_height = JDIMENSION(image.rows);
  info.input_components = image.channels();
  info.in_color_space = image.channels() == 1 ? JCS_GRAYSCALE : JCS_EXT_BGR;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<unsigned char*>(image.ptr(int(info.next_scanline)));
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return true;
}

// ------------------------------------------------------------------ others

AVCodecID sniff_codec(std::span<const unsigned char> b) {
  const auto starts = [&](const char* magic, size_t n, size_t at = 0) {
    return b.size() >= at + n && std::memcmp(b.data() + at, magic, n) == 0;
  };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return AV_CODEC_ID_PNG;
  if (starts("BM", 2)) return AV_CODEC_ID_BMP;
  if (starts("II*\0", 4) || starts("MM\0*", 4)) return AV_CODEC_ID_TIFF;
  if (starts("RIFF", 4) && starts("WEBP", 4, 8)) return AV_CODEC_ID_WEBP;
  if (b.size() >= 2 && b[0] == 'P') {
    if (b[1] == '4') return AV_CODEC_ID_PBM;
    if (b[1] == '5') return AV_CODEC_ID_PGM;
    if (b[1] == '6') return AV_CODEC_ID_PPM;
  }
  return AV_CODEC_ID_NONE;
}

struct CodecContextFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};

// A decoded picture as 8-bit BGR: the common layouts converted exactly,
// the rest by libswscale.
cv::Mat picture_to_bgr(const AVFrame& f) {
  const cv::Mat plane(f.height, f.width, CV_8UC1, f.data[0], size_t(f.linesize[0]));
  const auto view = [&](int type) { return cv::Mat(f.height, f.width, type, f.data[0], size_t(f.linesize[0])); };
  cv::Mat bgr;
  switch (f.format) {
    case AV_PIX_FMT_BGR24:
      view(CV_8UC3).copyTo(bgr);
      return bgr;
    case AV_PIX_FMT_RGB24:
      cv::cvtColor(view(CV_8UC3), bgr, cv::COLOR_RGB2BGR);
      return bgr;
    case AV_PIX_FMT_RGBA:
      cv::cvtColor(view(CV_8UC4), bgr, cv::COLOR_RGBA2BGR);
      return bgr;
    case AV_PIX_FMT_BGRA:
      cv::cvtColor(view(CV_8UC4), bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    case AV_PIX_FMT_GRAY8:
      cv::cvtColor(plane, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case AV_PIX_FMT_PAL8: {
      bgr.create(f.height, f.width, CV_8UC3);
      const auto* palette = reinterpret_cast<const uint32_t*>(f.data[1]);
      for (int y = 0; y < f.height; ++y) {
        for (int x = 0; x < f.width; ++x) {
          const uint32_t argb = palette[plane.at<unsigned char>(y, x)];
          bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(argb & 0xff, (argb >> 8) & 0xff, (argb >> 16) & 0xff);
        }
      }
      return bgr;
    }
    default: {
      SwsContext* sws = sws_getContext(f.width, f.height, AVPixelFormat(f.format), f.width, f.height, AV_PIX_FMT_BGR24,
                                       SWS_BICUBIC, nullptr, nullptr, nullptr);
      if (sws == nullptr) return {};
      bgr.create(f.height, f.width, CV_8UC3);
      uint8_t* target[4] = {bgr.data, nullptr, nullptr, nullptr};
      const int target_step[4] = {int(bgr.step), 0, 0, 0};
      sws_scale(sws, f.data, f.linesize, 0, f.height, target, target_step);
      sws_freeContext(sws);
      return bgr;
    }
  }
}

cv::Mat decode_with_libavcodec(std::span<const unsigned char> bytes) {
  const AVCodecID id = sniff_codec(bytes);
  const AVCodec* codec = id == AV_CODEC_ID_NONE ? nullptr : avcodec_find_decoder(id);
  if (codec == nullptr) return {};
  quiet_ffmpeg_log();
  const std::unique_ptr<AVCodecContext, CodecContextFree> context(avcodec_alloc_context3(codec));
  const std::unique_ptr<AVPacket, PacketFree> packet(av_packet_alloc());
  const std::unique_ptr<AVFrame, FrameFree> frame(av_frame_alloc());
  if (!context || !packet || !frame || avcodec_open2(context.get(), codec, nullptr) < 0) return {};
  if (bytes.size() > size_t(INT32_MAX) || av_new_packet(packet.get(), int(bytes.size())) < 0) return {};
  std::memcpy(packet->data, bytes.data(), bytes.size());
  if (avcodec_send_packet(context.get(), packet.get()) < 0) return {};
  avcodec_send_packet(context.get(), nullptr);
  if (avcodec_receive_frame(context.get(), frame.get()) < 0) return {};
  return picture_to_bgr(*frame);
}

}  // namespace

cv::Mat decode_image(std::span<const unsigned char> bytes) {
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) {
    cv::Mat image;
    int orientation = 1;
    if (!decode_jpeg(bytes, image, orientation)) return {};
    apply_orientation(image, orientation);
    return image;
  }
  return decode_with_libavcodec(bytes);
}

cv::Mat read_image(const fs::path& path) {
  const auto bytes = read_binary_file(path);
  return bytes ? decode_image(*bytes) : cv::Mat();
}

std::vector<unsigned char> encode_png(const cv::Mat& image) {
  if (image.depth() == CV_16U) return encode_png16(image);
  if (image.empty() || image.depth() != CV_8U ||
      (image.channels() != 1 && image.channels() != 3 && image.channels() != 4))
    throw Error("cannot encode a PNG from this image: it needs 8 or 16 bits and 1, 3 or 4 channels");
  const auto describe = [&]() {
    png_image header{};
    header.version = PNG_IMAGE_VERSION;
    header.width = png_uint_32(image.cols);
    header.height = png_uint_32(image.rows);
    header.format = image.channels() == 1 ? PNG_FORMAT_GRAY : image.channels() == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_BGRA;
    header.flags = PNG_IMAGE_FLAG_FAST;  // the speed of cv::imwrite's default (zlib level 1)
    return header;
  };
  const auto row_stride = png_int_32(image.step / image.elemSize1());  // in components
  png_image header = describe();
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&header, nullptr, &size, 0, image.data, row_stride, nullptr))
    throw Error(std::string("cannot encode a PNG: ") + header.message);
  std::vector<unsigned char> png(size);
  header = describe();
  if (!png_image_write_to_memory(&header, png.data(), &size, 0, image.data, row_stride, nullptr))
    throw Error(std::string("cannot encode a PNG: ") + header.message);
  png.resize(size);
  return png;
}

std::vector<unsigned char> encode_jpeg(const cv::Mat& image, int quality) {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw Error("cannot encode a JPEG from this image: it needs 8 bits and 1 or 3 channels");
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  const bool encoded = encode_jpeg_into(image, std::clamp(quality, 1, 100), &buffer, &size);
  const std::unique_ptr<unsigned char, decltype(&std::free)> owned(buffer, &std::free);
  if (!encoded || buffer == nullptr) throw Error("cannot encode a JPEG");
  return std::vector<unsigned char>(buffer, buffer + size);
}

void write_image(const fs::path& path, const cv::Mat& image) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  std::vector<unsigned char> bytes;
  if (ext == ".png") {
    bytes = encode_png(image);
  } else if (ext == ".jpg" || ext == ".jpeg") {
    bytes = encode_jpeg(image);
  } else {
    throw Error("cannot write " + path.string() + ": an image is written as .png, .jpg or .jpeg");
  }
  write_binary_file(path, bytes.data(), bytes.size());
}

}  // namespace facecap
