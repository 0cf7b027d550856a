#pragma once
// The eyeballs of the ICT model as spheres that turn to a gaze direction.
//
// ICT's eyeballs do not turn with its eyeLookIn/Out/Up/Down shapes, which
// move only the lids, so gaze is two angles of its own: each eyeball turns
// about the mean of its vertices, and its front-most vertex (the pupil)
// lies at the sphere's radius from there. What a camera sees of the eye's
// direction is the centre of the iris's outer ring (the limbus): a circle of
// kIrisRadiusCm on the sphere, whose centre lies inside the sphere, on the
// gaze axis, at iris_depth from the eyeball's centre. Seen at an angle, the
// iris's centre is not where the pupil's front projects (about 1 mm apart
// at 20 degrees).
//
// Directions are in the model frame (x toward the subject's left, y up, z out
// of the face): yaw > 0 looks toward the subject's left, pitch > 0 looks up,
// (0, 0) looks straight out of the face.
#include <array>
#include <cmath>

#include "facecap/core/camera.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"

namespace facecap {

// Eye 0: the subject's right eye (iBUG 36-41); eye 1: the left (42-47).
// The human iris is 11.7 mm across on average.
inline constexpr double kIrisRadiusCm = 0.585;

// The model's vertices of eye 0's or eye 1's eyeball.
inline const Region& eyeball_region(int eye) { return eye == 0 ? regions::kEyeballRight : regions::kEyeballLeft; }

struct EyeballGeometry {
  std::array<Vec3d, 2> centre;  // model frame, cm
  std::array<double, 2> radius{0.0, 0.0};
  std::array<int, 2> pupil_vertex{0, 0};
  // Unit direction from the centre to the pupil at rest (ICT's eyes look
  // about 2 degrees outward, so not quite +z).
  std::array<Vec3d, 2> rest_axis{Vec3d::UnitZ(), Vec3d::UnitZ()};
  // Distance from the eyeball's centre to the plane of the iris's outer ring.
  double iris_depth(int eye) const { return std::sqrt(radius[eye] * radius[eye] - kIrisRadiusCm * kIrisRadiusCm); }
};

// For an identity (its leading modes; missing ones are zeros).
EyeballGeometry eyeball_geometry(const FaceModel& model, const Eigen::VectorXd& identity);
// For a whole head's positions (3 x all vertices, model frame).
EyeballGeometry head_eyeball_geometry(const FaceModel& model, const Positions& head);

// (yaw, pitch) in degrees of a direction in the model frame.
Vec2d gaze_angles_deg(const Vec3d& direction);
// The rotation that turns a straight-ahead eye (+z) to gaze (yaw, pitch).
Mat3d gaze_rotation(double yaw_deg, double pitch_deg);

// The axis of an eye turned by gaze (yaw, pitch) from rest.
Vec3d turned_axis(const EyeballGeometry& eyes, int eye, double yaw_deg, double pitch_deg);

// Turns both eyeballs of a head's model-frame positions (3 x all vertices)
// from straight ahead to the gaze.
void turn_eyeballs(const EyeballGeometry& eyes, double yaw_deg, double pitch_deg, Positions& head);

// Where the centre of the iris of an eye turned to `direction` (model frame)
// projects, the iris's plane at `depth` from the eyeball's centre (by
// default the sphere's iris_depth).
Vec2d project_iris_centre(const EyeballGeometry& eyes, int eye, const Vec3d& direction, const HeadPose& pose,
                          const PinholeCamera& camera);
Vec2d project_iris_centre(const EyeballGeometry& eyes, int eye, const Vec3d& direction, double depth,
                          const HeadPose& pose, const PinholeCamera& camera);

}  // namespace facecap
