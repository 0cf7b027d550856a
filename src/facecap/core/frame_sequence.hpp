#pragma once
// Frames handed over in order, numbered as in the video: whether each
// follows the last one (a frame without a face between breaks the run, and
// what compares consecutive frames starts afresh).

namespace facecap {

class FrameSequence {
 public:
  // Takes `index` as the last frame; false where it does not follow the
  // one before. -1 (unknown) follows, and anything follows it.
  bool follows(int index) {
    const bool gap = index >= 0 && last_ >= 0 && index != last_ + 1;
    last_ = index;
    return !gap;
  }

 private:
  int last_ = -1;
};

}  // namespace facecap
