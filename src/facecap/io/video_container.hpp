#pragma once
// A video file's container opened with libavformat, and the facts facecap
// reads from it (InputInfo), shared by probe_video_file and the decoder so
// that a video opened to be decoded is probed on the same opening.
#include <atomic>
#include <filesystem>

#include "facecap/io/input.hpp"

struct AVCodecContext;
struct AVFormatContext;

namespace facecap {

// avformat_open_input and avformat_find_stream_info. The caller owns the
// result (avformat_close_input). Throws facecap::Error naming the file when
// it is not a video file or is corrupt.
AVFormatContext* open_video_container(const std::filesystem::path& path);

// Width, height, frame rate, frame count (and those of them that lie past
// the end of a file cut short), audio and duration of the container
// `open_video_container` gave. Throws facecap::Error naming the file where
// it has no video stream or no frame size.
InputInfo video_facts(const AVFormatContext& container, const std::filesystem::path& path);

// From now on the errors libavcodec logs while `decoder` decodes, and the
// line its error resilience logs where it conceals damage ("concealing ..."),
// add to `errors` instead of going nowhere (quiet_ffmpeg_log), under frame
// threading from the threads' copies of the context too: the damage it met
// in the stream. decode_error_flags says the same of a frame, but
// under frame threading it comes out on the frame or not by the threads'
// timing. `errors` must outlive the decoder; the context's `opaque` is taken.
void count_decoding_errors(AVCodecContext& decoder, std::atomic<int>& errors);

}  // namespace facecap
