#pragma once
// H.264 output (mp4, mov or mkv, by the path's extension) through the ffmpeg program: frames go down a pipe (raw YUV
// 4:2:0), the input's audio track (when it has one) is muxed in, and the file is written under a temporary name that
// finish() renames to the final one. A writer destroyed without finish() (an error, an interruption) removes its
// temporary file and leaves whatever was at the final path untouched.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/video_encoding.hpp"

namespace facecap {

// The container a video path asks for, as ffmpeg names it: .mp4 and .m4v
// "mp4", .mov "mov", .mkv "matroska" (case-insensitive); all hold H.264, AAC
// and the tags of VideoWriterOptions::metadata. Throws facecap::Error naming
// the choices for any other name (.avi, .webm, none), rather than writing an
// mp4 under a name that says otherwise.
std::string video_container(const std::filesystem::path& path);

struct VideoWriterOptions {
  int width = 0;
  int height = 0;
  double fps = 30.0;
  // Take the audio track from this file (the input), if it has one.
  std::optional<std::filesystem::path> audio_source;
  // Where in that audio to start (runs that start part-way), and whether to
  // end it with the last frame written (runs that stop early): a frame count
  // over the mean rate would misplace the end of a variable-rate video.
  double audio_start = 0;
  bool audio_ends_with_video = false;
  // Container metadata (mp4/mov/Matroska tags), e.g. {"comment", "..."}.
  std::map<std::string, std::string> metadata;
  VideoEncoding encoding;
};

class VideoWriter {
 public:
  // Starts ffmpeg; throws facecap::Error when the output folder is not
  // writable or ffmpeg cannot be started.
  VideoWriter(const std::filesystem::path& path, VideoWriterOptions options);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Appends one BGR frame of the declared size (other sizes are resized).
  void write(const cv::Mat& bgr);
  // The same for a frame shown at `time` (seconds; Frame::time) on the input's
  // timeline. The output has a constant rate (options.fps), and each frame
  // takes the slot nearest its time, counted from the first frame's: where a
  // variable-rate input leaves slots empty, the frame before fills them; a
  // frame whose slot is taken is dropped. So the picture keeps to the input's
  // sound. For a constant-rate input, every frame takes the next slot.
  void write(const cv::Mat& bgr, double time);
  // Closes the stream, waits for ffmpeg and renames the file into place.
  void finish();
  int frames_written() const { return frames_; }
  // The encoder process's CPU time (user and system, ms), once finish() has
  // waited for it: a benchmark's share of the cores that went to encoding.
  double encoder_cpu_ms() const { return encoder_cpu_ms_; }

 private:
  void stop_encoder(bool kill);
  void send(const cv::Mat& yuv);  // one frame (encoder_frame()) down the pipe
  // ffmpeg's last error line, or where it left none, full_disk_note's.
  std::string encoder_log() const;

  std::filesystem::path path_;
  VideoWriterOptions options_;
  AtomicFile file_;
  std::filesystem::path log_path_;
  std::optional<RegisteredTempFile> log_registered_;  // ffmpeg's messages, removed once read
  int pipe_fd_ = -1;
  int pid_ = -1;
  int frames_ = 0;
  double encoder_cpu_ms_ = 0;
  bool finished_ = false;
  double first_time_ = 0;  // the first timed frame's time
  cv::Mat last_;           // the last timed frame sent (as sent), for the slots after it
};

// An output of the input's size and rate carrying its audio (if any) from
// where the input starts (InputInfo::first_frame), ending with the last
// frame written when max_frames stops the run before the input's end (0: all),
// encoded as `encoding` says.
VideoWriterOptions output_like(const InputInfo& input, int max_frames = 0, const VideoEncoding& encoding = {});

// Where frame `index` (at `time`, Frame::time) goes on an output_like(input)
// video, for VideoWriter::write(bgr, time): its time on a video's or a
// camera's timeline; a still's and a folder's frames one after another.
double output_time(const InputInfo& input, int index, double time);

}  // namespace facecap
