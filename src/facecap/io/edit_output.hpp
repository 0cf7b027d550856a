#pragma once
// Where an edit's frames go (transform, swap): an H.264 video with the
// input's sound (video_writer.hpp), or, where the input is one photo, a still
// image (.png, .jpg, .jpeg) that carries the synthetic-media marks in its own
// metadata (marked_image.hpp). Either is written atomically.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "facecap/io/input.hpp"
#include "facecap/io/video_writer.hpp"

namespace facecap {

// Checks, before any work, that `path` names an output an input of `kind`
// can give: a video container (video_container()) for anything, or a still
// image for a photo. Throws facecap::Error naming the choices otherwise.
void check_edit_output(const std::filesystem::path& path, InputKind kind);

class EditOutput {
 public:
  // `options.metadata` holds the marks (synthetic_metadata()). Throws as
  // check_edit_output() does.
  EditOutput(const std::filesystem::path& path, InputKind kind, VideoWriterOptions options);
  ~EditOutput();
  EditOutput(const EditOutput&) = delete;
  EditOutput& operator=(const EditOutput&) = delete;

  // One BGR frame shown at `time` (VideoWriter::write); a still keeps the last.
  void write(const cv::Mat& bgr, double time);
  // Completes the file (an unfinished output leaves nothing at the path).
  void finish();
  bool is_still() const { return video_ == nullptr; }
  // A video's encoder CPU time after finish() (VideoWriter::encoder_cpu_ms); 0 for a still.
  double encoder_cpu_ms() const { return video_ ? video_->encoder_cpu_ms() : 0.0; }

 private:
  std::filesystem::path path_;
  std::map<std::string, std::string> tags_;
  std::unique_ptr<VideoWriter> video_;
  cv::Mat still_;
};

}  // namespace facecap
