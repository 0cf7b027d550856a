#pragma once
// x264's settings for the videos facecap writes (VideoWriter).
#include <string>

namespace facecap {

// x264's settings for an output video.
struct VideoEncoding {
  int crf = 18;                     // quality, 0 (lossless) to 51: lower is better, 18 is visually lossless
  std::string preset = "veryfast";  // speed against size at that quality (kX264Presets)
};

// x264's presets, fastest first.
inline constexpr const char* kX264Presets[] = {"ultrafast", "superfast", "veryfast", "faster",  "fast",
                                               "medium",    "slow",      "slower",   "veryslow"};

// Throws facecap::Error for a crf outside 0-51 or a preset x264 lacks.
void check_encoding(const VideoEncoding& encoding);

}  // namespace facecap
