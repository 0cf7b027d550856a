#include "facecap/io/edit_output.hpp"

#include "facecap/core/error.hpp"
#include "facecap/io/marked_image.hpp"

namespace facecap {

namespace fs = std::filesystem;

void check_edit_output(const fs::path& path, InputKind kind) {
  if (!is_still_image_path(path)) {
    if (kind != InputKind::kImage) {
      video_container(path);  // throws naming the video containers
      return;
    }
    try {
      video_container(path);
    } catch (const Error&) {
      throw Error("cannot write to " + path.string() +
                  ": its name must end in .png, .jpg or .jpeg (an image) or .mp4, .m4v, .mov or .mkv (a video)");
    }
    return;
  }
  if (kind != InputKind::kImage)
    throw Error("cannot write a video to " + path.string() +
                ": an image output (.png, .jpg, .jpeg) is for a photo input; name a .mp4, .m4v, .mov or .mkv");
}

EditOutput::EditOutput(const fs::path& path, InputKind kind, VideoWriterOptions options)
    : path_(path), tags_(options.metadata) {
  check_edit_output(path, kind);
  if (is_still_image_path(path)) {
    ensure_writable_file(fs::absolute(path));
  } else {
    video_ = std::make_unique<VideoWriter>(path, std::move(options));
  }
}

EditOutput::~EditOutput() = default;

void EditOutput::write(const cv::Mat& bgr, double time) {
  if (video_) {
    video_->write(bgr, time);
  } else {
    still_ = bgr.clone();
  }
}

void EditOutput::finish() {
  if (video_) {
    video_->finish();
  } else {
    write_marked_image(path_, still_, tags_);
  }
}

}  // namespace facecap
