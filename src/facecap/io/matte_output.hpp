#pragma once
// An edit's matte (`swap --matte`, `transform --matte`): a greyscale video,
// or an image for a photo, of how much of each output pixel the edit put
// there (255: the new face; 0: the input), frame for frame with the edit's
// output, so that a compositor can redo or adjust the composite. It carries
// the edit's synthetic-media marks, described as its matte, and no sound.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/io/edit_output.hpp"
#include "facecap/io/synthetic_mark.hpp"

namespace facecap {

// The checks before any work: `matte` is writable, can hold an edit of an
// input of `kind` (check_edit_output), and is neither the edit's `output`
// nor one of its `inputs`.
void check_matte_output(const std::filesystem::path& matte, const std::filesystem::path& output, InputKind kind,
                        const std::vector<std::string>& inputs);

class MatteOutput {
 public:
  // `like`: the edit's output options (size, rate); `edit_mark`: its marks.
  MatteOutput(const std::filesystem::path& path, const std::filesystem::path& output, InputKind kind,
              VideoWriterOptions like, SyntheticMark edit_mark);

  // One frame: `alpha` (CV_32F in [0, 1], or CV_8U) over `window` of a
  // frame of `size`, zero elsewhere; an empty alpha is a frame with none.
  void write(const cv::Mat& alpha, cv::Rect window, cv::Size size, double time);
  // Completes the file and its sidecar.
  void finish();

 private:
  std::filesystem::path path_;
  SyntheticMark mark_;
  EditOutput out_;
};

}  // namespace facecap
