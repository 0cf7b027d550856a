#include "facecap/model/jaw_contour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace facecap {

namespace {

// Face vertices at the height of `candidate`, from it toward the middle of
// the face (as far in as `inner_x`), outermost first.
std::vector<int> march_line(const Eigen::Map<const Positions>& neutral, int candidate, float inner_x) {
  const Region& face = regions::kFace;
  const Vec3f c = neutral.col(candidate);
  const float side = c.x() < 0 ? -1.0f : 1.0f;
  std::vector<std::pair<float, int>> line;
  for (int v = face.first_vertex; v <= face.last_vertex; ++v) {
    const Vec3f p = neutral.col(v);
    if (p.x() * side <= 0) continue;
    if (std::abs(p.y() - c.y()) > 0.22f) continue;
    if (std::abs(p.x()) > std::abs(c.x()) + 0.05f || std::abs(p.x()) < inner_x) continue;
    if (p.z() < c.z() - 0.05f) continue;  // stay on the front surface
    line.emplace_back(-std::abs(p.x()), v);
  }
  std::sort(line.begin(), line.end());
  std::vector<int> out{candidate};
  for (const auto& [key, v] : line) {
    if (v != candidate) out.push_back(v);
  }
  return out;
}

}  // namespace

JawContour build_jaw_contour(const FaceModel& model) {
  Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
  JawContour contour;
  const LandmarkMap& lm = model.landmarks;
  contour.chin = lm.vertices[8];
  for (int k = 0; k < 17; ++k) {
    if (k == 8) {
      contour.lines[k] = {contour.chin};
      continue;
    }
    const int candidate = k < 8 ? lm.jaw_right[k] : lm.jaw_left[k - 9];
    // The landmark map's own vertex for this landmark lies on the front of
    // the cheek; the line runs a little beyond it.
    contour.lines[k] = march_line(neutral, candidate, std::abs(neutral(0, lm.vertices[k])) * 0.55f);
  }
  // Extended lists: the right one runs ear to chin; the left one chin to ear.
  for (int v : lm.jaw_right_extended)
    contour.right_path.push_back(march_line(neutral, v, std::abs(neutral(0, v)) * 0.55f));
  for (auto it = lm.jaw_left_extended.rbegin(); it != lm.jaw_left_extended.rend(); ++it) {
    contour.left_path.push_back(march_line(neutral, *it, std::abs(neutral(0, *it)) * 0.55f));
  }
  return contour;
}

namespace {

// How far outward along `lateral` a vertex projects ((x, y) / z orders
// points as their images for any focal length).
double outward_measure(const Vec3d& p, bool right_side, const Vec2d& lateral) {
  const double outward = right_side ? -1.0 : 1.0;  // subject's right side appears at image left
  return outward * (lateral.x() * p.x() + lateral.y() * p.y()) / p.z();
}

// The line vertex that projects furthest outward.
int outermost(const std::vector<int>& line, bool right_side, const CameraPositionFn& camera_position,
              const Vec2d& lateral) {
  double best = -std::numeric_limits<double>::infinity();
  int best_v = line.front();
  for (int v : line) {
    const double x = outward_measure(camera_position(v), right_side, lateral);
    if (x > best) {
      best = x;
      best_v = v;
    }
  }
  return best_v;
}

}  // namespace

Vec2d image_lateral(const Mat3d& model_to_camera) {
  const Vec2d axis = model_to_camera.col(0).head<2>();
  // A head turned side-on (yaw near 90 degrees) shows its axis end-on.
  if (!(axis.norm() > 1e-6)) return {1, 0};
  constexpr double kQuarter = std::numbers::pi / 2;
  constexpr double kFrom = kQuarter / 6, kTo = kQuarter / 2;  // 15 and 45 degrees
  const double roll = std::atan2(axis.y(), axis.x());
  const double quarter = kQuarter * std::round(roll / kQuarter);
  const double off = roll - quarter;  // from the nearest of the image's axes
  const double used = quarter + off * std::clamp((std::abs(off) - kFrom) / (kTo - kFrom), 0.0, 1.0);
  return {std::cos(used), std::sin(used)};
}

std::array<int, 17> silhouette_vertices(const JawContour& contour, const CameraPositionFn& camera_position,
                                        const Vec2d& lateral) {
  std::array<int, 17> out{};
  for (int k = 0; k < 17; ++k) out[k] = outermost(contour.lines[k], k < 8, camera_position, lateral);
  return out;
}

std::vector<int> silhouette_path(const JawContour& contour, bool right_side, const CameraPositionFn& camera_position,
                                 const Vec2d& lateral) {
  const auto& lines = right_side ? contour.right_path : contour.left_path;
  std::vector<int> out;
  out.reserve(lines.size() + 1);
  for (const auto& line : lines) out.push_back(outermost(line, right_side, camera_position, lateral));
  out.push_back(contour.chin);
  return out;
}

std::array<int, 17> silhouette_vertices(const JawContour& contour, const Positions& face_positions,
                                        const Mat3d& model_to_camera, const Vec3d& translation) {
  return silhouette_vertices(
      contour, [&](int v) -> Vec3d { return model_to_camera * face_positions.col(v).cast<double>() + translation; },
      image_lateral(model_to_camera));
}

std::array<int, 68> landmark_vertices_for_pose(const FaceModel& model, const JawContour& contour,
                                               const Positions& face_positions, const Mat3d& model_to_camera,
                                               const Vec3d& translation) {
  std::array<int, 68> out{};
  std::copy(model.landmarks.vertices.begin(), model.landmarks.vertices.end(), out.begin());
  const auto jaw = silhouette_vertices(contour, face_positions, model_to_camera, translation);
  std::copy(jaw.begin(), jaw.end(), out.begin());
  return out;
}

}  // namespace facecap
