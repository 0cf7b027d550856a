#include "facecap/io/video_encoding.hpp"

#include <algorithm>
#include <iterator>

#include "facecap/core/error.hpp"

namespace facecap {

void check_encoding(const VideoEncoding& encoding) {
  if (encoding.crf < 0 || encoding.crf > 51)
    throw Error("x264's crf must lie in 0-51, not " + std::to_string(encoding.crf));
  if (std::find_if(std::begin(kX264Presets), std::end(kX264Presets),
                   [&](const char* p) { return encoding.preset == p; }) == std::end(kX264Presets))
    throw Error("x264 has no preset '" + encoding.preset + "' (ultrafast ... veryslow)");
}

}  // namespace facecap
