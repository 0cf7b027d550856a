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
  int faces = 0;                // faces the detector finds in the first frame
  std::vector<Box> face_boxes;  // their boxes, left to right (pixels)
};

// Throws facecap::Error for inputs that cannot be read.
ProbeReport probe_input(const std::string& spec);

}  // namespace facecap
