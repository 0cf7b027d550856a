#include "facecap/io/livelink_csv.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace facecap {

namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

// The model's name of an ARKit shape: "EyeBlinkLeft" -> "eyeBlink_L"
// (sided), "JawLeft" -> "jawLeft" (a shape of its own, tried first).
std::string camel(std::string name) {
  name[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  return name;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

}  // namespace

const std::vector<std::string>& LiveLinkCsv::arkit_names() {
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
                                                 "TongueOut"};
  return names;
}

LiveLinkCsv::LiveLinkCsv(const std::vector<std::string>& expression_names, double fps) : fps_(fps > 0 ? fps : 30.0) {
  for (const std::string& arkit : arkit_names()) {
    std::vector<int> from;
    const std::string name = camel(arkit);
    if (const int k = index_of(expression_names, name); k >= 0) {
      from.push_back(k);
    } else if (name.ends_with("Left") || name.ends_with("Right")) {
      const bool left = name.ends_with("Left");
      const std::string base = name.substr(0, name.size() - (left ? 4 : 5));
      if (const int k = index_of(expression_names, base + (left ? "_L" : "_R")); k >= 0) from.push_back(k);
    } else {
      // One ARKit shape that the model has in halves.
      for (const char* side : {"_L", "_R"})
        if (const int k = index_of(expression_names, name + side); k >= 0) from.push_back(k);
    }
    sources_.push_back(std::move(from));
  }
}

std::string LiveLinkCsv::header() const {
  std::string h = "Timecode,BlendShapeCount";
  for (const std::string& name : arkit_names()) h += "," + name;
  h += ",HeadYaw,HeadPitch,HeadRoll,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,RightEyePitch,RightEyeRoll";
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

std::string LiveLinkCsv::row(double seconds, const Eigen::VectorXf& weights, const Pose& pose) const {
  std::string r = timecode(seconds, fps_) + ",61";
  char buf[32];
  auto add = [&](double v) {
    std::snprintf(buf, sizeof(buf), ",%.7g", std::isfinite(v) ? v : 0.0);
    r += buf;
  };
  for (const std::vector<int>& from : sources_) {
    double sum = 0;
    for (const int k : from) sum += k < weights.size() ? weights[k] : 0.0f;
    add(from.empty() ? 0.0 : sum / double(from.size()));
  }
  for (int k = 0; k < 3; ++k) add(pose.head_yaw_pitch_roll_deg[k] * kRadiansPerDegree);
  add(pose.left_eye_deg.x() * kRadiansPerDegree);
  add(pose.left_eye_deg.y() * kRadiansPerDegree);
  add(0.0);
  add(pose.right_eye_deg.x() * kRadiansPerDegree);
  add(pose.right_eye_deg.y() * kRadiansPerDegree);
  add(0.0);
  return r;
}

}  // namespace facecap
