#pragma once
// `facecap probe`: what an input is (size, rate, length, audio) and the
// faces its first frame shows, where they are (for `--face X,Y`).
#include <string>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

struct ProbeReport {
  InputInfo info;
  int faces = 0;                // faces the detector finds in the frame below
  std::vector<Box> face_boxes;  // their boxes, left to right (pixels)
  int face_frame = -1;          // that frame's index: the first read, or the first with a face
};

// The faces of the frame at `start_seconds` (FrameSource::seek), or, with
// `scan_frames` > 1, of the first of that many frames that shows one (a video
// that opens on black or a title). Throws facecap::Error for inputs that
// cannot be read.
ProbeReport probe_input(const std::string& spec, double start_seconds = 0, int scan_frames = 1);

}  // namespace facecap
