#include "facecap/io/livelink_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "facecap/core/error.hpp"

namespace facecap {

const std::vector<std::string>& LiveLinkCsv::columns() {
  static const std::vector<std::string> names = {"EyeBlinkLeft",
                                                 "EyeLookDownLeft",
                                                 "EyeLookInLeft",
                                                 "EyeLookOutLeft",
                                                 "EyeLookUpLeft",
                                                 "EyeSquintLeft",
                                                 "EyeWideLeft",
                                                 "EyeBlinkRight",
                                                 "EyeLookDownRight",
                                                 "EyeLookInRight",
                                                 "EyeLookOutRight",
                                                 "EyeLookUpRight",
                                                 "EyeSquintRight",
                                                 "EyeWideRight",
                                                 "JawForward",
                                                 "JawRight",
                                                 "JawLeft",
                                                 "JawOpen",
                                                 "MouthClose",
                                                 "MouthFunnel",
                                                 "MouthPucker",
                                                 "MouthRight",
                                                 "MouthLeft",
                                                 "MouthSmileLeft",
                                                 "MouthSmileRight",
                                                 "MouthFrownLeft",
                                                 "MouthFrownRight",
                                                 "MouthDimpleLeft",
                                                 "MouthDimpleRight",
                                                 "MouthStretchLeft",
                                                 "MouthStretchRight",
                                                 "MouthRollLower",
                                                 "MouthRollUpper",
                                                 "MouthShrugLower",
                                                 "MouthShrugUpper",
                                                 "MouthPressLeft",
                                                 "MouthPressRight",
                                                 "MouthLowerDownLeft",
                                                 "MouthLowerDownRight",
                                                 "MouthUpperUpLeft",
                                                 "MouthUpperUpRight",
                                                 "BrowDownLeft",
                                                 "BrowDownRight",
                                                 "BrowInnerUp",
                                                 "BrowOuterUpLeft",
                                                 "BrowOuterUpRight",
                                                 "CheekPuff",
                                                 "CheekSquintLeft",
                                                 "CheekSquintRight",
                                                 "NoseSneerLeft",
                                                 "NoseSneerRight",
                                                 "TongueOut",
                                                 "HeadYaw",
                                                 "HeadPitch",
                                                 "HeadRoll",
                                                 "LeftEyeYaw",
                                                 "LeftEyePitch",
                                                 "LeftEyeRoll",
                                                 "RightEyeYaw",
                                                 "RightEyePitch",
                                                 "RightEyeRoll"};
  return names;
}

LiveLinkCsv::LiveLinkCsv(double fps) : fps_(fps > 0 ? fps : 30.0) {
  for (const std::string& column : columns()) {
    const int k = LiveLinkFace::index_of(column);
    if (k < 0) throw Error("internal: Live Link column " + column + " has no value");
    order_.push_back(k);
  }
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
