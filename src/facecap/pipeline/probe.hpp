#pragma once
// `facecap probe`: what an input is (size, rate, length, audio) and the
// faces its first frame shows, where they are (for `--face X,Y`): as the
// tracker's first search finds them, upright first, at twice the size where
// there are none, in the frame turned by multiples of 45 degrees where there
// are still none (a camera on its side, someone lying down), and then
// halfway between those turns.
#include <string>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

struct ProbeFace {
  Box box;  // in the frame (pixels), around the face however it is turned
  // The turn (a multiple of 45 degrees, clockwise; 0 upright; 22.5 off one
  // where only the half turns show the face) of the view where the detector
  // was surest of the face: its roll to within about 30.
  float roll_degrees = 0;
};

struct ProbeReport {
  InputInfo info;
  int faces = 0;                 // faces the detector finds in the first frame
  std::vector<ProbeFace> found;  // where they are, left to right
};

// Throws facecap::Error for inputs that cannot be read.
ProbeReport probe_input(const std::string& spec);

}  // namespace facecap
