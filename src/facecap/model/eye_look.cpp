#include "facecap/model/eye_look.hpp"

#include <algorithm>

namespace facecap {

EyeLookShapes::EyeLookShapes(const FaceModel& model) {
  const std::array<const char*, 8> names = {"eyeLookOut_L", "eyeLookIn_R", "eyeLookIn_L",   "eyeLookOut_R",
                                            "eyeLookUp_L",  "eyeLookUp_R", "eyeLookDown_L", "eyeLookDown_R"};
  for (size_t k = 0; k < names.size(); ++k) index_[k] = model.expression_index(names[k]);
}

std::vector<std::pair<int, double>> EyeLookShapes::weights(const Vec2d& gaze_deg) const {
  const auto share = [](double degrees) { return std::clamp(degrees / kEyeLookFullDeg, 0.0, 1.0); };
  const double left = share(gaze_deg.x()), right = share(-gaze_deg.x());
  const double up = share(gaze_deg.y()), down = share(-gaze_deg.y());
  const std::array<double, 8> values = {left, left, right, right, up, up, down, down};
  std::vector<std::pair<int, double>> out;
  for (size_t k = 0; k < index_.size(); ++k)
    if (index_[k] >= 0) out.emplace_back(index_[k], values[k]);
  return out;
}

std::vector<int> EyeLookShapes::indices() const {
  std::vector<int> out;
  for (int k : index_)
    if (k >= 0) out.push_back(k);
  return out;
}

}  // namespace facecap
