#pragma once
// A video stream decoded with libavformat and libavcodec and converted to
// 8-bit BGR as OpenCV's FFmpeg back-end converts it (bicubic libswscale to
// BGR24 at the coded size, cropped to the picture, turned upright by the
// stream's display matrix), so the same pixels, without linking OpenCV's
// videoio: its GStreamer, gPhoto2, DC1394 and image-codec dependencies cost
// every facecap process about 0.2 s of dynamic loading before main().
#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "facecap/io/input.hpp"

namespace facecap {

class VideoDecoder {
 public:
  // Throws facecap::Error naming the file when it cannot be opened (cut
  // short before its index, say), or holds no video stream that libavcodec
  // can decode. One cut short after its index opens, and reads to the cut.
  static VideoDecoder open_file(const std::filesystem::path& path);
  // /dev/videoN through libavdevice's video4linux2 input; libavdevice is
  // loaded only here, the first time a camera is opened.
  static VideoDecoder open_camera(int index);

  ~VideoDecoder();
  VideoDecoder(VideoDecoder&&) noexcept;
  VideoDecoder& operator=(VideoDecoder&&) noexcept;

  // The next frame in display order; false at the end of the stream. A
  // damaged packet is skipped (its frame is lost, or decoded with its
  // damage concealed), not the end.
  bool read(cv::Mat& bgr);
  // The time of the frame read last, in seconds from the stream's start, or
  // NaN where it carries no timestamp.
  double time() const;
  // Whether the frame read last came with damage concealed: libavcodec
  // flagged it corrupt or filled in parts it could not decode (a corrupt
  // stream; frames predicted from it carry the damage on unflagged).
  bool damaged() const;
  // Packets the decoder refused so far (from the start, or the seek), as
  // `ffmpeg` counts its decode errors: each one's frame is lost (and frames
  // predicted from it may be too). A corrupt stream, say one whose index
  // gives a sample a few bytes too many, so the packets after it are misread.
  int refused_packets() const;
  // Once read() has returned false: why the stream ended before the end its
  // container declares (a file cut short, a damaged index, a read error),
  // as a clause for a message ("the last 13 of the 27 frames its index
  // lists could not be read (...)"); "" where it read to that end, or where
  // the container declares none (a Matroska file, a camera).
  std::string early_end() const;
  // The frame rate the container gives (average, else nominal), or 0.
  double nominal_fps() const;
  // A file's facts, as probe_video_file gives them, read on the decoder's
  // own opening of the container (a camera's are left empty).
  const InputInfo& facts() const;
  // Makes the next read() give the first frame whose time is at or after
  // `seconds`, and returns its index in display order (the number of frames
  // before it), or -1 where the stream ends before. The timestamps of the
  // packets, read without decoding, say which frame that is; decoding starts
  // at the keyframe before it.
  int seek(double seconds);

 private:
  struct Impl;
  explicit VideoDecoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
