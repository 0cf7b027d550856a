#pragma once
// Eye gaze from the iris centres (iris.hpp) on the fitted head: not part of
// the dissertation's fit (§4.1 fits the face only). Each eye's direction
// runs from its eyeball's centre (eyeballs.hpp) to the point where the
// camera ray through the iris centre meets the sphere of the iris ring's
// centres about it (radius iris_depth; its point nearest the ray where the
// ray passes beside it). Directions and angles are
// head-relative, in the model frame (eyeballs.hpp).

#include <array>
#include <optional>

#include "facecap/core/camera.hpp"
#include "facecap/detect/iris.hpp"
#include "facecap/model/eyeballs.hpp"

namespace facecap {

struct EyeGaze {
  Vec3d direction = Vec3d::UnitZ();         // model frame, unit
  Vec3d camera_direction = Vec3d::UnitZ();  // the same in the camera frame
  Vec3d camera_iris = Vec3d::Zero();        // the iris's centre in the camera frame, cm
  bool ray_missed = false;                  // the iris ray passed beside the eyeball
};

struct GazeEstimate {
  std::array<std::optional<EyeGaze>, 2> eyes;  // eye 0: the subject's right
  bool valid() const { return eyes[0] || eyes[1]; }
  // Both eyes' directions averaged (or the one seen), model frame, unit.
  Vec3d direction() const;
  Vec2d angles_deg() const { return gaze_angles_deg(direction()); }
};

using IrisCentres = std::array<std::optional<Vec2d>, 2>;

GazeEstimate estimate_gaze(const EyeballGeometry& eyes, const HeadPose& pose, const PinholeCamera& camera,
                           const IrisCentres& iris);

// The irises of a fitted frame, searched at the size the head's depth gives
// them (iris.hpp), and the gaze they show.
struct GazeMeasurement {
  IrisPair irises;
  GazeEstimate gaze;
};
GazeMeasurement measure_gaze(const cv::Mat& grey, const Landmarks& observed, const EyeballGeometry& eyes,
                             const HeadPose& pose, const PinholeCamera& camera);

}  // namespace facecap
