#include "facecap/detect/landmarks.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "facecap/core/error.hpp"

namespace facecap {

Box bounding_box(std::span<const Vec2f> points) {
  if (points.empty()) return {};
  float x0 = points[0].x(), x1 = x0, y0 = points[0].y(), y1 = y0;
  for (const Vec2f& p : points) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  return {x0, y0, x1 - x0, y1 - y0};
}

float outer_eye_distance(const Landmarks& lm) { return (lm[36] - lm[45]).norm(); }

float landmark_nme(const Landmarks& estimate, const Landmarks& truth) {
  double sum = 0.0;
  for (int i = 0; i < kNumLandmarks; ++i) sum += (estimate[i] - truth[i]).norm();
  return static_cast<float>(sum / kNumLandmarks / std::max(1e-6f, outer_eye_distance(truth)));
}

Landmarks read_pts(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("landmark file not found: " + path.string());
  std::string line;
  int declared = -1;
  bool in_points = false;
  std::vector<Vec2f> points;
  while (std::getline(in, line)) {
    if (line.find("n_points") != std::string::npos) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) declared = std::atoi(line.c_str() + colon + 1);
    } else if (line.find('{') != std::string::npos) {
      in_points = true;
    } else if (line.find('}') != std::string::npos) {
      in_points = false;
    } else if (in_points) {
      std::istringstream ss(line);
      float x = 0, y = 0;
      if (!(ss >> x >> y)) throw Error("malformed landmark file " + path.string() + ": bad point line '" + line + "'");
      points.emplace_back(x - 1.0f, y - 1.0f);
    }
  }
  if (declared != kNumLandmarks || points.size() != static_cast<size_t>(kNumLandmarks)) {
    throw Error("landmark file " + path.string() + " must hold 68 points (found " + std::to_string(points.size()) +
                ")");
  }
  Landmarks lm;
  std::copy(points.begin(), points.end(), lm.begin());
  return lm;
}

}  // namespace facecap
