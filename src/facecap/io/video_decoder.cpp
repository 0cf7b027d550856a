#include "facecap/io/video_decoder.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/display.h>
#include <libavutil/error.h>
#include <libswscale/swscale.h>
}

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <thread>

#include "facecap/core/error.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/video_container.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// Consecutive packets that give no frame before a stream counts as ended
// (OpenCV's back-end gives up after as many).
constexpr int kMaxFruitlessPackets = 4096;

// The camera input lives in libavdevice, whose own dependencies (SDL, PulseAudio,
// X11 and more) only a camera needs: it is loaded then, not linked. Only the
// one built with the linked libavformat will do (their major versions move
// together).
std::string avdevice_library() { return "libavdevice.so." + std::to_string(LIBAVFORMAT_VERSION_MAJOR); }

const AVInputFormat* camera_input_format() {
  static const AVInputFormat* format = [] {
    void* handle = ::dlopen(avdevice_library().c_str(), RTLD_NOW | RTLD_GLOBAL);
    auto* register_all = handle ? reinterpret_cast<void (*)()>(::dlsym(handle, "avdevice_register_all")) : nullptr;
    if (register_all == nullptr) return static_cast<const AVInputFormat*>(nullptr);
    register_all();
    return av_find_input_format("video4linux2");
  }();
  return format;
}

}  // namespace

struct VideoDecoder::Impl {
  std::string name;  // for messages
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  AVFrame* converted = av_frame_alloc();  // BGR24 at the coded size
  SwsContext* sws = nullptr;
  int stream = -1;
  int rotation = 0;  // clockwise degrees that turn a decoded frame upright
  bool flushing = false;
  double last_time = std::numeric_limits<double>::quiet_NaN();
  bool last_damaged = false;
  std::atomic<int> decoding_errors{0};  // count_decoding_errors
  int decoding_errors_seen = 0;         // by the frame read last
  bool holding = false;                 // `frame` is the one seek() found, for the next read()
  // How reading ended (early_end): the latest decode timestamp of the
  // stream's packets demuxed and how many there were, av_read_frame's code
  // at the end, and whether kMaxFruitlessPackets ended it.
  int64_t last_dts = AV_NOPTS_VALUE;
  int demuxed = 0;
  int end_code = 0;
  bool gave_up = false;
  int refused = 0;  // packets the decoder refused, and frames it failed on (refused_packets)
  InputInfo facts;  // a file's (video_facts)

  ~Impl() {
    sws_freeContext(sws);
    av_frame_free(&converted);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }

  AVStream* video() const { return format->streams[stream]; }

  // Opens `url` with `input` as its demuxer (a camera).
  void open(const std::string& url, const AVInputFormat* input) {
    quiet_ffmpeg_log();
    int code = avformat_open_input(&format, url.c_str(), input, nullptr);
    if (code < 0) throw Error("cannot open " + name + ": " + av_error_text(code));
    code = avformat_find_stream_info(format, nullptr);
    if (code < 0) throw Error("cannot read " + name + ": " + av_error_text(code));
  }

  // Finds the opened container's best video stream and its decoder.
  void open_decoder() {
    if (!packet || !frame || !converted) throw Error("cannot decode " + name + ": out of memory");
    const AVCodec* decoder = nullptr;
    int code = 0;
    stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
    if (stream < 0 || decoder == nullptr)
      throw Error("cannot decode " + name + ": no video stream libavcodec can decode");
    codec = avcodec_alloc_context3(decoder);
    if (codec == nullptr || avcodec_parameters_to_context(codec, video()->codecpar) < 0)
      throw Error("cannot decode " + name + ": its video stream's parameters are unusable");
    // One decoding thread a core, as OpenCV's back-end used (libavcodec's own
    // choice, one more than the cores, competed with capture on the 2-core VM).
    codec->thread_count = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
    count_decoding_errors(*codec, decoding_errors);
    code = avcodec_open2(codec, decoder, nullptr);
    if (code < 0) throw Error("cannot decode " + name + ": " + av_error_text(code));
    if (const auto* matrix =
            reinterpret_cast<const int32_t*>(av_stream_get_side_data(video(), AV_PKT_DATA_DISPLAYMATRIX, nullptr))) {
      // As OpenCV's back-end reads it: a phone's portrait clip (tagged
      // rotate=90, a display matrix of 90 here) is turned 90 degrees clockwise.
      const double angle = av_display_rotation_get(matrix);
      if (std::isfinite(angle)) rotation = ((int(std::lround(angle)) % 360) + 360) % 360;
    }
  }

  double seconds_of(int64_t timestamp) const {
    if (timestamp == AV_NOPTS_VALUE) return std::numeric_limits<double>::quiet_NaN();
    const int64_t start = video()->start_time == AV_NOPTS_VALUE ? 0 : video()->start_time;
    return double(timestamp - start) * av_q2d(video()->time_base);
  }

  // Decodes the next frame into `frame`; false at the end. A packet the
  // decoder refuses, or a frame it fails on, is passed over, up to
  // kMaxFruitlessPackets in a row.
  bool decode_next() {
    int fruitless = 0;
    while (true) {
      const int received = avcodec_receive_frame(codec, frame);
      if (received == 0) return true;
      if (received == AVERROR_EOF || (received == AVERROR(EAGAIN) && flushing)) return false;
      if (received != AVERROR(EAGAIN)) {
        ++refused;
        if (++fruitless > kMaxFruitlessPackets) return give_up();
        continue;
      }
      if (const int code = av_read_frame(format, packet); code < 0) {
        end_code = code;
        flushing = true;
        // Drain the frames the decoder holds; under frame threading the
        // decoding error of the last packet sent may come back here.
        const int drained = avcodec_send_packet(codec, nullptr);
        refused += drained < 0 && drained != AVERROR_EOF;
        continue;
      }
      const bool ours = packet->stream_index == stream;
      if (ours) note_demuxed(*packet);
      const int sent = ours ? avcodec_send_packet(codec, packet) : 0;
      av_packet_unref(packet);
      if (!ours) continue;
      refused += sent < 0;
      if (sent < 0 && ++fruitless > kMaxFruitlessPackets) return give_up();
      if (sent == 0) fruitless = 0;
    }
  }

  void note_demuxed(const AVPacket& packet) {
    ++demuxed;
    const int64_t dts = packet.dts != AV_NOPTS_VALUE ? packet.dts : packet.pts;
    if (dts != AV_NOPTS_VALUE && (last_dts == AV_NOPTS_VALUE || dts > last_dts)) last_dts = dts;
  }

  bool give_up() {
    gave_up = true;
    return false;
  }

  // Frames the container's sample index lists that reading never reached
  // (it ended at an error, or where the file is cut short or its index
  // damaged, at an end-of-file the demuxer reports early); 0 where there is
  // no such index to count by. MP4 and QuickTime list every sample
  // (nb_frames, from the sample table) and libavformat indexes each, up to
  // a damaged entry, where it stops; elsewhere an index that lists every
  // frame is used as it is. Samples an edit list leaves out stay indexed
  // (marked discarded), so a trimmed file reads to its index's end.
  int frames_unread() const {
    AVStream* const s = video();
    const int entries = avformat_index_get_entries_count(s);
    const bool sample_index = std::string_view(format->iformat->name).starts_with("mov,") || entries == s->nb_frames;
    if (s->nb_frames <= 0 || entries <= 0 || entries > s->nb_frames || !sample_index) return 0;
    if (demuxed == 0) return int(s->nb_frames);  // not one packet was read
    if (last_dts == AV_NOPTS_VALUE) return 0;    // packets without times: no telling
    int reached = 0;                             // entries at or before the last packet demuxed
    for (int k = 0; k < entries; ++k) reached += avformat_index_get_entry(s, k)->timestamp <= last_dts;
    return int(s->nb_frames) - reached;
  }

  // `frame` as 8-bit BGR: converted at the coded size by bicubic libswscale
  // into a 32-byte-aligned buffer, as OpenCV's back-end does (so the same
  // conversion routine and the same pixels), then cropped and turned upright.
  cv::Mat to_bgr() {
    const int width = std::max(codec->coded_width, frame->width);
    const int height = std::max(codec->coded_height, frame->height);
    sws = sws_getCachedContext(sws, width, height, AVPixelFormat(frame->format), width, height, AV_PIX_FMT_BGR24,
                               SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (sws == nullptr) throw Error("cannot convert " + name + "'s frames to BGR");
    cv::Mat bgr;
    const int row_bytes = 3 * width;
    if (width == frame->width && row_bytes % 32 == 0) {
      // Straight into the frame handed out (its rows as the 32-byte aligned
      // frame's, so the same conversion), the coded rows past the picture
      // left unseen: no copy of the picture. A spare row, as libav pads its
      // buffers, for a conversion that writes whole vectors.
      cv::Mat coded(height + 1, width, CV_8UC3);
      uint8_t* const planes[4] = {coded.data, nullptr, nullptr, nullptr};
      const int strides[4] = {row_bytes, 0, 0, 0};
      sws_scale(sws, frame->data, frame->linesize, 0, height, planes, strides);
      bgr = coded.rowRange(0, frame->height);
    } else {
      bgr = converted_copy(width, height);
    }
    if (rotation == 90) cv::rotate(bgr, bgr, cv::ROTATE_90_CLOCKWISE);
    if (rotation == 180) cv::rotate(bgr, bgr, cv::ROTATE_180);
    if (rotation == 270) cv::rotate(bgr, bgr, cv::ROTATE_90_COUNTERCLOCKWISE);
    return bgr;
  }

  // The frame converted into `converted` (32-byte aligned rows, as OpenCV's
  // back-end converts), its picture copied out.
  cv::Mat converted_copy(int width, int height) {
    if (converted->width != width || converted->height != height) {
      av_frame_unref(converted);
      converted->format = AV_PIX_FMT_BGR24;
      converted->width = width;
      converted->height = height;
      if (av_frame_get_buffer(converted, 32) != 0) throw Error("cannot decode " + name + ": out of memory");
    }
    sws_scale(sws, frame->data, frame->linesize, 0, height, converted->data, converted->linesize);
    cv::Mat bgr;
    cv::Mat(frame->height, frame->width, CV_8UC3, converted->data[0], size_t(converted->linesize[0])).copyTo(bgr);
    return bgr;
  }

  double frame_time() const { return seconds_of(frame->best_effort_timestamp); }

  // Back to the keyframe at or before `timestamp`, the decoder emptied.
  void rewind_to(int64_t timestamp) {
    av_seek_frame(format, stream, timestamp, AVSEEK_FLAG_BACKWARD);
    avcodec_flush_buffers(codec);
    flushing = false;
    holding = false;
    last_dts = AV_NOPTS_VALUE;
    demuxed = 0;
    end_code = 0;
    gave_up = false;
    refused = 0;
  }

  int64_t first_timestamp() const { return video()->start_time == AV_NOPTS_VALUE ? 0 : video()->start_time; }
};

VideoDecoder::VideoDecoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
VideoDecoder::~VideoDecoder() = default;
VideoDecoder::VideoDecoder(VideoDecoder&&) noexcept = default;
VideoDecoder& VideoDecoder::operator=(VideoDecoder&&) noexcept = default;

VideoDecoder VideoDecoder::open_file(const fs::path& path) {
  auto impl = std::make_unique<Impl>();
  impl->name = path.string();
  impl->format = open_video_container(path);
  impl->facts = video_facts(*impl->format, path);
  impl->open_decoder();
  return VideoDecoder(std::move(impl));
}

VideoDecoder VideoDecoder::open_camera(int index) {
  auto impl = std::make_unique<Impl>();
  impl->name = "camera " + std::to_string(index);
  const AVInputFormat* input = camera_input_format();
  if (input == nullptr) {
    throw Error("cannot open camera " + std::to_string(index) + ": libavdevice's video4linux2 input is missing (" +
                avdevice_library() + ", from the ffmpeg package)");
  }
  impl->open("/dev/video" + std::to_string(index), input);
  impl->open_decoder();
  return VideoDecoder(std::move(impl));
}

bool VideoDecoder::read(cv::Mat& bgr) {
  Impl& d = *impl_;
  if (d.holding) {
    d.holding = false;
  } else if (!d.decode_next()) {
    return false;
  }
  bgr = d.to_bgr();
  d.last_time = d.frame_time();
  // Errors logged since the frame before: under frame threading they may
  // belong to a frame the threads decode ahead, so the flag can fall a frame
  // or two early or late.
  const int errors = d.decoding_errors.load(std::memory_order_relaxed);
  d.last_damaged = d.frame->decode_error_flags != 0 || (d.frame->flags & AV_FRAME_FLAG_CORRUPT) != 0 ||
                   errors != d.decoding_errors_seen;
  d.decoding_errors_seen = errors;
  return true;
}

double VideoDecoder::time() const { return impl_->last_time; }

std::string VideoDecoder::early_end() const {
  const Impl& d = *impl_;
  if (d.gave_up) {
    return "after " + std::to_string(kMaxFruitlessPackets) +
           " packets in a row that gave no picture, the rest was not read (a corrupt stream)";
  }
  const int unread = d.frames_unread();
  const std::string frames =
      std::to_string(unread) + " of the " + std::to_string(d.video()->nb_frames) + " frames its index lists";
  if (d.facts.frames_past_end > 0 && unread > 0)
    return "the file is cut short: the last " + frames + " lie past its end";
  if (d.end_code < 0 && d.end_code != AVERROR_EOF) {
    return "reading stopped at an error (" + av_error_text(d.end_code) + ")" +
           (unread > 0 ? ", with the last " + frames + " unread" : "");
  }
  if (unread > 0) return "the last " + frames + " could not be read (the file is cut short or its index damaged)";
  return "";
}

bool VideoDecoder::damaged() const { return impl_->last_damaged; }

int VideoDecoder::refused_packets() const { return impl_->refused; }

const InputInfo& VideoDecoder::facts() const { return impl_->facts; }

double VideoDecoder::nominal_fps() const {
  const AVRational rate = av_guess_frame_rate(impl_->format, impl_->video(), nullptr);
  return rate.num > 0 && rate.den > 0 ? av_q2d(rate) : 0.0;
}

int VideoDecoder::seek(double seconds) {
  Impl& d = *impl_;
  constexpr double kTolerance = 1e-6;
  // Which frame: the packets' timestamps from the start, read without
  // decoding. The frames before `seconds` are counted; the earliest at or
  // after it is the target. Decode order is not display order, but no packet
  // after one whose dts is past the target can be shown before it.
  d.rewind_to(d.first_timestamp());
  int before = 0;
  bool every_packet_timed = true;
  int64_t target = AV_NOPTS_VALUE;
  double target_seconds = 0;
  while (av_read_frame(d.format, d.packet) >= 0) {
    if (d.packet->stream_index == d.stream) {
      const double shown = d.seconds_of(d.packet->pts);
      if (!std::isfinite(shown)) {
        every_packet_timed = false;
      } else if (shown < seconds - kTolerance) {
        ++before;
      } else if (target == AV_NOPTS_VALUE || shown < target_seconds) {
        target = d.packet->pts;
        target_seconds = shown;
      }
    }
    const bool past = target != AV_NOPTS_VALUE && d.packet->stream_index == d.stream &&
                      d.packet->dts != AV_NOPTS_VALUE && d.seconds_of(d.packet->dts) > target_seconds;
    av_packet_unref(d.packet);
    if (past || !every_packet_timed) break;
  }
  if (!every_packet_timed) {
    // No timestamps to count by: decode from the start.
    d.rewind_to(d.first_timestamp());
    const double fps = nominal_fps();
    for (int index = 0; d.decode_next(); ++index) {
      const double shown = std::isfinite(d.frame_time()) || fps <= 0 ? d.frame_time() : index / fps;
      if (!(shown < seconds - kTolerance)) {
        d.holding = true;
        return index;
      }
    }
    return -1;
  }
  if (target == AV_NOPTS_VALUE) return -1;
  // Decode from the keyframe at or before the target to the target.
  d.rewind_to(target);
  while (d.decode_next()) {
    if (d.frame_time() >= target_seconds - kTolerance) {
      d.holding = true;
      return before;
    }
  }
  return -1;
}

}  // namespace facecap
