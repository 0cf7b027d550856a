// Container-level facts about a video file, read with libavformat.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
}

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

#include "facecap/core/error.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/video_container.hpp"

namespace facecap {

namespace {

struct FormatCloser {
  void operator()(AVFormatContext* ctx) const { avformat_close_input(&ctx); }
};

std::unique_ptr<AVFormatContext, FormatCloser> open_container(const std::filesystem::path& path) {
  quiet_ffmpeg_log();
  AVFormatContext* raw = nullptr;
  const int open_code = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
  if (open_code < 0) {
    throw Error("cannot read " + path.string() + ": not a video file or corrupt (" + av_error_text(open_code) + ")");
  }
  return std::unique_ptr<AVFormatContext, FormatCloser>(raw);
}

// libav's log callback: prints nothing; an error from a decoder that
// count_decoding_errors set up is counted, and so is the line with which
// libavcodec's error resilience says it concealed damage ("concealing %d DC,
// %d AC, %d MV errors in %c frame", logged as information: a keyframe hit
// part-way says nothing else).
void libav_log_sink(void* source, int level, const char* format, va_list) {
  const bool concealed = format != nullptr && std::strncmp(format, "concealing ", 11) == 0;
  if (source == nullptr || (level > AV_LOG_ERROR && !concealed)) return;
  if (*static_cast<const AVClass* const*>(source) != avcodec_get_class()) return;
  const auto* context = static_cast<const AVCodecContext*>(source);
  if (context->opaque != nullptr && av_codec_is_decoder(context->codec))
    static_cast<std::atomic<int>*>(context->opaque)->fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

void quiet_ffmpeg_log() {
  av_log_set_level(AV_LOG_QUIET);
  static std::once_flag once;  // the callback is read by libav's threads: set before any decoder runs, once
  std::call_once(once, [] { av_log_set_callback(libav_log_sink); });
}

void count_decoding_errors(AVCodecContext& decoder, std::atomic<int>& errors) {
  quiet_ffmpeg_log();
  decoder.opaque = &errors;
}

std::string av_error_text(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, text, sizeof(text));
  return text;
}

std::map<std::string, std::string> read_container_tags(const std::filesystem::path& path) {
  const auto ctx = open_container(path);
  std::map<std::string, std::string> tags;
  const AVDictionaryEntry* e = nullptr;
  while ((e = av_dict_get(ctx->metadata, "", e, AV_DICT_IGNORE_SUFFIX)) != nullptr) tags[e->key] = e->value;
  return tags;
}

AVFormatContext* open_video_container(const std::filesystem::path& path) {
  auto ctx = open_container(path);
  const int info_code = avformat_find_stream_info(ctx.get(), nullptr);
  if (info_code < 0) {
    throw Error("cannot read " + path.string() + ": corrupt or truncated video (" + av_error_text(info_code) + ")");
  }
  return ctx.release();
}

InputInfo probe_video_file(const std::filesystem::path& path) {
  const std::unique_ptr<AVFormatContext, FormatCloser> ctx(open_video_container(path));
  return video_facts(*ctx, path);
}

namespace {

// The samples of `stream` its index places at or past the end of the file:
// an MP4 with its index first (faststart), cut short after it, as a download
// that stopped leaves it. Those before the cut can still be read (the one
// the cut splits, in part).
int samples_past_end(const AVFormatContext& container, const AVStream& stream) {
  const int64_t file_size = container.pb ? avio_size(container.pb) : -1;
  if (file_size <= 0) return 0;
  AVStream* const indexed = const_cast<AVStream*>(&stream);  // avformat_index_get_entry reads, but is not const
  int past = 0;
  for (int k = avformat_index_get_entries_count(indexed) - 1;
       k >= 0 && avformat_index_get_entry(indexed, k)->pos >= file_size; --k)
    ++past;
  return past;
}

}  // namespace

InputInfo video_facts(const AVFormatContext& container, const std::filesystem::path& path) {
  const AVFormatContext* const ctx = &container;
  InputInfo info;
  info.spec = path.string();
  info.kind = InputKind::kVideo;
  const AVStream* video = nullptr;
  for (unsigned i = 0; i < ctx->nb_streams; ++i) {
    const AVStream* s = ctx->streams[i];
    if (s->codecpar->codec_type == AVMEDIA_TYPE_VIDEO && video == nullptr &&
        !(s->disposition & AV_DISPOSITION_ATTACHED_PIC)) {
      video = s;
    }
    if (s->codecpar->codec_type == AVMEDIA_TYPE_AUDIO && !info.audio) {
      info.audio = true;
      if (s->duration != AV_NOPTS_VALUE && s->duration > 0)
        info.audio_duration = double(s->duration) * av_q2d(s->time_base);
    }
  }
  if (video == nullptr) throw Error("cannot read " + path.string() + ": it has no video stream");
  info.width = video->codecpar->width;
  info.height = video->codecpar->height;
  if (info.width <= 0 || info.height <= 0) {
    throw Error("cannot read " + path.string() +
                ": its video has no frame size (no picture in it could be decoded: a corrupt stream, or one cut "
                "from the middle of another without its headers)");
  }
  const AVRational rate = video->avg_frame_rate.num > 0 ? video->avg_frame_rate : video->r_frame_rate;
  info.fps = rate.den > 0 ? av_q2d(rate) : 0.0;
  if (video->duration != AV_NOPTS_VALUE && video->duration > 0) {
    info.duration = double(video->duration) * av_q2d(video->time_base);
  } else if (ctx->duration > 0) {
    info.duration = double(ctx->duration) / AV_TIME_BASE;
  }
  if (video->nb_frames > 0) {
    info.frames = static_cast<int>(video->nb_frames);
    info.frames_past_end = std::min(samples_past_end(*ctx, *video), info.frames);
  } else if (info.duration > 0 && info.fps > 0) {
    info.frames = static_cast<int>(std::lround(info.duration * info.fps));
  }
  return info;
}

}  // namespace facecap
