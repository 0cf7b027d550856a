#pragma once
// `facecap probe`: what an input is (size, rate, length, audio) and how many
// faces its first frame shows.
#include <string>

#include "facecap/io/input.hpp"

namespace facecap {

struct ProbeReport {
  InputInfo info;
  int faces = 0;  // faces the detector finds in the first frame
};

// Throws facecap::Error for inputs that cannot be read.
ProbeReport probe_input(const std::string& spec);

}  // namespace facecap
