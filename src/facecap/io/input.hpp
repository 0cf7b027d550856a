#pragma once
// Frame sources: a video file, a still image, a folder of images, or a camera
// ("cam:N"). Opening validates the input and throws facecap::Error with a
// one-line message naming the problem (missing, empty, a folder with no
// images, not a video, undecodable).
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace facecap {

enum class InputKind { kVideo, kImage, kImageFolder, kCamera };
const char* to_string(InputKind kind);

struct InputInfo {
  std::string spec;  // what the user gave
  InputKind kind = InputKind::kVideo;
  int width = 0;
  int height = 0;
  double fps = 0.0;           // 0 for stills
  int frames = -1;            // -1 when unknown (camera)
  int frames_past_end = 0;    // of `frames`, those a video cut short lists past its end: they cannot be read
  bool audio = false;         // has an audio stream
  double audio_duration = 0;  // seconds of the first audio stream, 0 when unknown or none
  double duration = 0;        // seconds, 0 when unknown
  int first_frame = 0;        // the frame reading starts at (open_input's start_seconds)
  double first_time = 0;      // ...and its time, seconds (a video's timestamp: see Frame::time)
};

// Whether the frames' times mean anything: a video's and a camera's do; a
// still's and an image folder's are all 0.
inline bool has_timeline(const InputInfo& info) {
  return info.kind == InputKind::kVideo || info.kind == InputKind::kCamera;
}

// The time of the first frame reading starts at (InputInfo::first_frame).
inline double start_time(const InputInfo& info) { return info.first_time; }

struct Frame {
  cv::Mat image;  // BGR, 8 bit; empty when this frame could not be decoded
  int index = 0;
  // Seconds from the start: a video file's own timestamp for the frame, so
  // that a variable-rate video (a phone's) keeps its timing (index / fps
  // would drift from it, and edits from their sound); index / fps for a
  // camera; 0 for stills and folders.
  double time = 0.0;
  std::string error;     // why `image` is empty, for per-frame status
  bool damaged = false;  // a video's frame decoded with damage concealed (VideoDecoder::damaged)
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const InputInfo& info() const = 0;
  // The next frame; false at the end of the input.
  virtual bool read(Frame& frame) = 0;
  // Once read() has returned false: why a video ended before the end its
  // container declares, a clause for a message (VideoDecoder::early_end);
  // "" where it did not, and for anything but a video.
  virtual std::string early_end() const { return ""; }
  // Packets of a video the decoder refused so far, their frames lost
  // (VideoDecoder::refused_packets); 0 for anything but a video.
  virtual int refused_packets() const { return 0; }
  // Before the first read: start at the first frame at or after `seconds`;
  // frames keep their index and time on the input's timeline. Only a video
  // file has a timeline to start into: anything else throws facecap::Error,
  // as does a time past the video's end.
  virtual void seek(double seconds);
};

// The frame's image, or for a frame the input could not give a black one of
// the input's size, so that output videos keep every frame in its place.
cv::Mat image_or_black(const Frame& frame, const InputInfo& info);

// Opens an input, reading from `start_seconds` on (FrameSource::seek).
std::unique_ptr<FrameSource> open_input(const std::string& spec, double start_seconds = 0);

// Width, height, frame rate, frame count, audio and duration of a video file
// (via libavformat); throws facecap::Error when the file is not a readable video.
InputInfo probe_video_file(const std::filesystem::path& path);

// Silences libav's own log, set before each video or image is opened: a
// damaged stream would print a line per broken macroblock ("error while
// decoding MB ...") between facecap's own lines. Such frames still decode
// (with their damage, which Frame::damaged marks) and are tracked or lost.
void quiet_ffmpeg_log();
// FFmpeg's words for one of its error codes (AVERROR(...)).
std::string av_error_text(int code);

// The container's metadata tags (mp4 udta/ilst), keys as FFmpeg names them.
std::map<std::string, std::string> read_container_tags(const std::filesystem::path& path);

bool is_image_path(const std::filesystem::path& path);

// The images of a folder (by their extension; not its subfolders'), in name
// order, as a folder input reads them. Throws facecap::Error where there are
// none.
std::vector<std::filesystem::path> folder_images(const std::filesystem::path& dir);

}  // namespace facecap
