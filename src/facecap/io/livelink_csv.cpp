#include "facecap/io/livelink_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace facecap {

const std::vector<std::string>& LiveLinkCsv::columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> c(LiveLinkFace::names().begin(), LiveLinkFace::names().end());
    // The app's takes order two pairs the other way round from its stream.
    for (const auto& [a, b] : {std::pair{"JawLeft", "JawRight"}, std::pair{"MouthLeft", "MouthRight"}})
      std::swap(c[LiveLinkFace::index_of(a)], c[LiveLinkFace::index_of(b)]);
    return c;
  }();
  return names;
}

LiveLinkCsv::LiveLinkCsv(double fps) : fps_(fps > 0 ? fps : 30.0) {
  for (const std::string& column : columns()) order_.push_back(LiveLinkFace::index_of(column));
}

std::string LiveLinkCsv::header() const {
  std::string h = "Timecode,BlendShapeCount";
  for (const std::string& name : columns()) h += "," + name;
  return h;
}

std::string LiveLinkCsv::timecode(double seconds, double fps) {
  const double frames = std::max(0.0, seconds) * fps;
  const long long whole = static_cast<long long>(std::floor(frames + 1e-6));
  const int per_second = std::max(1, static_cast<int>(std::lround(fps)));
  const long long s = whole / per_second;
  const int millis = std::clamp(static_cast<int>(std::lround((frames - double(whole)) * 1000.0)), 0, 999);
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%02lld:%02lld:%02lld:%02lld.%03d", s / 3600, (s / 60) % 60, s % 60,
                whole % per_second, millis);
  return buf;
}

std::string LiveLinkCsv::row(double seconds, const LiveLinkFace::Values& values) const {
  std::string r = timecode(seconds, fps_) + ",61";
  char buf[32];
  for (const int k : order_) {
    std::snprintf(buf, sizeof(buf), ",%.7g", double(values[k]));
    r += buf;
  }
  return r;
}

}  // namespace facecap
