#include "facecap/io/matte_output.hpp"

#include <opencv2/imgproc.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

VideoWriterOptions matte_options(VideoWriterOptions like, const SyntheticMark& mark) {
  like.audio_source.reset();
  like.encoding.crf = 0;  // x264's lossless mode: a matte's levels are its content
  like.metadata = synthetic_metadata(mark);
  return like;
}

SyntheticMark matte_mark(SyntheticMark mark, const fs::path& output) {
  mark.description = "The matte of an edit by facecap (255 where the new face is, 0 where the input shows) for " +
                     output.filename().string() + ". " + mark.description;
  mark.parameters["matte_of"] = output.string();
  return mark;
}

}  // namespace

void check_matte_output(const fs::path& matte, const fs::path& output, InputKind kind,
                        const std::vector<std::string>& inputs) {
  ensure_writable_file(fs::absolute(matte));
  check_edit_output(matte, kind);
  ensure_not_an_input(matte, inputs);
  if (fs::absolute(matte).lexically_normal() == fs::absolute(output).lexically_normal())
    throw Error("--matte " + matte.string() + " is the output itself: give the matte a name of its own");
}

MatteOutput::MatteOutput(const fs::path& path, const fs::path& output, InputKind kind, VideoWriterOptions like,
                         SyntheticMark edit_mark)
    : path_(path), mark_(matte_mark(std::move(edit_mark), output)), out_(path, kind, matte_options(like, mark_)) {}

void MatteOutput::write(const cv::Mat& alpha, cv::Rect window, cv::Size size, double time) {
  cv::Mat grey(size, CV_8U, cv::Scalar(0));
  window &= cv::Rect(0, 0, size.width, size.height);
  if (!alpha.empty() && window.area() > 0) {
    if (alpha.type() == CV_8U)
      alpha(cv::Rect(0, 0, window.width, window.height)).copyTo(grey(window));
    else
      alpha(cv::Rect(0, 0, window.width, window.height)).convertTo(grey(window), CV_8U, 255.0);
  }
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  out_.write(bgr, time);
}

void MatteOutput::finish() {
  out_.finish();
  write_synthetic_sidecar(path_, mark_);
}

}  // namespace facecap
