#include "facecap/model/eyeballs.hpp"

#include <cmath>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// One eye's sphere from its region's positions (3 x its vertices).
void set_eyeball(const FaceModel& model, int eye, const Positions& shaped, EyeballGeometry& g) {
  const Region& r = eyeball_region(eye);
  const Eigen::Map<const Positions> neutral(model.neutral.data() + 3 * r.first_vertex, 3, r.num_vertices());
  Eigen::Index front = 0;
  neutral.row(2).maxCoeff(&front);  // the pupil: the front-most vertex at rest
  g.centre[eye] = shaped.cast<double>().rowwise().mean();
  g.pupil_vertex[eye] = r.first_vertex + static_cast<int>(front);
  const Vec3d to_pupil = shaped.col(front).cast<double>() - g.centre[eye];
  g.radius[eye] = to_pupil.norm();
  g.rest_axis[eye] = to_pupil / g.radius[eye];
}

}  // namespace

EyeballGeometry eyeball_geometry(const FaceModel& model, const Eigen::VectorXd& identity) {
  EyeballGeometry g;
  for (int eye = 0; eye < 2; ++eye) {
    const Region& r = eyeball_region(eye);
    const Eigen::VectorXf shape = model.identity_shape(identity.cast<float>(), r);
    set_eyeball(model, eye, Eigen::Map<const Positions>(shape.data(), 3, r.num_vertices()), g);
  }
  return g;
}

EyeballGeometry head_eyeball_geometry(const FaceModel& model, const Positions& head) {
  if (head.cols() != model.num_vertices)
    throw Error("head_eyeball_geometry: the head does not have the model's vertices");
  EyeballGeometry g;
  for (int eye = 0; eye < 2; ++eye) {
    const Region& r = eyeball_region(eye);
    set_eyeball(model, eye, head.middleCols(r.first_vertex, r.num_vertices()), g);
  }
  return g;
}

Vec2d gaze_angles_deg(const Vec3d& d) {
  return {std::atan2(d.x(), d.z()) / kDegToRad, std::atan2(d.y(), std::hypot(d.x(), d.z())) / kDegToRad};
}

Mat3d gaze_rotation(double yaw_deg, double pitch_deg) {
  // Pitch about x (turning +z toward +y), then yaw about y (toward +x).
  const double yaw = yaw_deg * kDegToRad, pitch = pitch_deg * kDegToRad;
  Mat3d pitch_m, yaw_m;
  pitch_m << 1, 0, 0, 0, std::cos(pitch), std::sin(pitch), 0, -std::sin(pitch), std::cos(pitch);
  yaw_m << std::cos(yaw), 0, std::sin(yaw), 0, 1, 0, -std::sin(yaw), 0, std::cos(yaw);
  return yaw_m * pitch_m;
}

Vec3d turned_axis(const EyeballGeometry& eyes, int eye, double yaw_deg, double pitch_deg) {
  return gaze_rotation(yaw_deg, pitch_deg) * eyes.rest_axis[eye];
}

void turn_eyeballs(const EyeballGeometry& eyes, double yaw_deg, double pitch_deg, Positions& head) {
  const Eigen::Matrix3f r = gaze_rotation(yaw_deg, pitch_deg).cast<float>();
  for (int eye = 0; eye < 2; ++eye) {
    const Region& region = eyeball_region(eye);
    const Vec3f c = eyes.centre[eye].cast<float>();
    for (int v = region.first_vertex; v <= region.last_vertex; ++v) head.col(v) = c + r * (head.col(v) - c);
  }
}

Vec2d project_iris_centre(const EyeballGeometry& eyes, int eye, const Vec3d& direction, const HeadPose& pose,
                          const PinholeCamera& camera) {
  return project_iris_centre(eyes, eye, direction, eyes.iris_depth(eye), pose, camera);
}

Vec2d project_iris_centre(const EyeballGeometry& eyes, int eye, const Vec3d& direction, double depth,
                          const HeadPose& pose, const PinholeCamera& camera) {
  const Vec3d iris = eyes.centre[eye] + depth * direction.normalized();
  return camera.project(Vec3d(pose.model_to_camera_rotation() * iris + pose.translation));
}

}  // namespace facecap
