#include "facecap/fit/gaze.hpp"

#include <cmath>
#include <numbers>

#include "facecap/model/jaw_contour.hpp"

namespace facecap {

namespace {

double angle_deg(const Vec3d& a, const Vec3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
}

}  // namespace

Vec3d GazeEstimate::direction() const {
  Vec3d sum = Vec3d::Zero();
  for (const auto& e : eyes)
    if (e) sum += e->direction;
  return sum.norm() > 0 ? Vec3d(sum.normalized()) : Vec3d::UnitZ();
}

GazeEstimate estimate_gaze(const EyeballGeometry& eyes, const HeadPose& pose, const PinholeCamera& camera,
                           const IrisCentres& iris) {
  GazeEstimate out;
  const Mat3d rf = pose.model_to_camera_rotation();
  for (int eye = 0; eye < 2; ++eye) {
    if (!iris[eye]) continue;
    const Vec2d& u = *iris[eye];
    const Vec3d ray = Vec3d((u.x() - camera.cx) / camera.focal, (u.y() - camera.cy) / camera.focal, 1.0).normalized();
    const Vec3d centre = rf * eyes.centre[eye] + pose.translation;
    const double radius = eyes.iris_depth(eye);
    // |t ray - centre|^2 = radius^2: the nearer root is the side facing the camera.
    const double b = ray.dot(centre);
    const double disc = b * b - (centre.squaredNorm() - radius * radius);
    EyeGaze g;
    Vec3d on_sphere;
    if (disc >= 0.0) {
      on_sphere = (b - std::sqrt(disc)) * ray;
    } else {
      g.ray_missed = true;
      on_sphere = centre + radius * (b * ray - centre).normalized();
    }
    g.camera_direction = ((on_sphere - centre) / radius).normalized();
    g.camera_iris = on_sphere;
    g.direction = rf.transpose() * g.camera_direction;
    if (g.direction.allFinite() && angle_deg(g.direction, eyes.rest_axis[eye]) <= kMaxEyeTurnDeg) out.eyes[eye] = g;
  }
  if (out.eyes[0] && out.eyes[1] &&
      angle_deg(out.eyes[0]->direction, out.eyes[1]->direction) > kMaxEyeDisagreementDeg) {
    const bool right_farther =
        angle_deg(out.eyes[0]->direction, eyes.rest_axis[0]) > angle_deg(out.eyes[1]->direction, eyes.rest_axis[1]);
    out.eyes[right_farther ? 0 : 1].reset();
  }
  return out;
}

IrisCentres iris_centres(const IrisPair& irises) {
  IrisCentres out;
  for (int eye = 0; eye < 2; ++eye)
    if (irises[eye]) out[eye] = irises[eye]->centre;
  return out;
}

std::array<IrisExpectation, 2> expected_irises(const EyeballGeometry& eyes, const HeadPose& pose,
                                               const PinholeCamera& camera) {
  std::array<IrisExpectation, 2> out;
  const Mat3d rf = pose.model_to_camera_rotation();
  // Each eye's turn from the camera is taken in the plane of the view
  // direction and the head's left-right axis as the image shows it (x for an
  // upright head; locate_iris narrows the ellipse along the eye, which that
  // axis follows).
  const Vec2d lateral = image_lateral(rf);
  const Vec3d across(lateral.x(), lateral.y(), 0.0);
  for (int eye = 0; eye < 2; ++eye) {
    const Vec3d centre = rf * eyes.centre[eye] + pose.translation;
    if (!(centre.z() > 0.0)) continue;
    out[eye].radius_px = camera.focal * kIrisRadiusCm / centre.z();
    const Vec3d axis = rf * eyes.rest_axis[eye], to_camera = -centre;
    out[eye].aspect =
        std::abs(std::cos(std::atan2(axis.dot(across), axis.z()) - std::atan2(to_camera.dot(across), to_camera.z())));
  }
  return out;
}

IrisSearch iris_search(const cv::Mat& grey, const Landmarks& observed) {
  // A copy of the eyes alone: a search may wait for the identity solve, a
  // second of frames (30 whole 4K frames would be 250 MB).
  const cv::Rect crop = eye_crop(grey.size(), observed);
  return [eyes = crop.empty() ? cv::Mat() : grey(crop).clone(), origin = crop.tl(),
          observed](const std::array<IrisExpectation, 2>& expected) {
    IrisPair out;
    for (int eye = 0; eye < 2; ++eye)
      if (expected[eye].radius_px > 0.0) out[eye] = locate_iris(eyes, observed, eye, expected[eye], {}, origin);
    return out;
  };
}

}  // namespace facecap
