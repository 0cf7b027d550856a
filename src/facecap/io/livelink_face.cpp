#include "facecap/io/livelink_face.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace facecap {

namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

// The model's name of an ARKit shape: "EyeBlinkLeft" -> "eyeBlink_L"
// (sided), "JawLeft" -> "jawLeft" (a shape of its own, tried first).
std::string camel(std::string_view arkit) {
  std::string name(arkit);
  name[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  return name;
}

int model_index(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

}  // namespace

const std::array<std::string_view, LiveLinkFace::kValues>& LiveLinkFace::names() {
  static constexpr std::array<std::string_view, kValues> kNames = {"EyeBlinkLeft",
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
                                                                   "JawLeft",
                                                                   "JawRight",
                                                                   "JawOpen",
                                                                   "MouthClose",
                                                                   "MouthFunnel",
                                                                   "MouthPucker",
                                                                   "MouthLeft",
                                                                   "MouthRight",
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
  return kNames;
}

int LiveLinkFace::index_of(std::string_view name) {
  const auto& all = names();
  const auto it = std::find(all.begin(), all.end(), name);
  return it == all.end() ? -1 : static_cast<int>(it - all.begin());
}

LiveLinkFace::LiveLinkFace(const std::vector<std::string>& expression_names) {
  for (int s = 0; s < kShapes; ++s) {
    std::vector<int> from;
    const std::string name = camel(names()[s]);
    if (const int k = model_index(expression_names, name); k >= 0) {
      from.push_back(k);
    } else if (name.ends_with("Left") || name.ends_with("Right")) {
      const bool left = name.ends_with("Left");
      const std::string base = name.substr(0, name.size() - (left ? 4 : 5));
      if (const int k = model_index(expression_names, base + (left ? "_L" : "_R")); k >= 0) from.push_back(k);
    } else {
      // One ARKit shape that the model has in halves.
      for (const char* side : {"_L", "_R"})
        if (const int k = model_index(expression_names, name + side); k >= 0) from.push_back(k);
    }
    sources_.push_back(std::move(from));
  }
}

LiveLinkFace::Values LiveLinkFace::values(const Eigen::VectorXf& weights, const LiveLinkPose& pose) const {
  Values v{};
  for (int s = 0; s < kShapes; ++s) {
    double sum = 0;
    for (const int k : sources_[s]) sum += k < weights.size() ? weights[k] : 0.0f;
    v[s] = sources_[s].empty() ? 0.0f : static_cast<float>(sum / double(sources_[s].size()));
  }
  const double angles_deg[9] = {pose.head_yaw_pitch_roll_deg.x(),
                                pose.head_yaw_pitch_roll_deg.y(),
                                pose.head_yaw_pitch_roll_deg.z(),
                                pose.left_eye_deg.x(),
                                pose.left_eye_deg.y(),
                                0.0,  // an eye's roll: the irises do not show it
                                pose.right_eye_deg.x(),
                                pose.right_eye_deg.y(),
                                0.0};
  for (int k = 0; k < 9; ++k) v[kShapes + k] = static_cast<float>(angles_deg[k] * kRadiansPerDegree);
  for (float& x : v)
    if (!std::isfinite(x)) x = 0.0f;
  return v;
}

}  // namespace facecap
