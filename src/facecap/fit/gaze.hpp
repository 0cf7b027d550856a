#pragma once
// Eye gaze from the iris centres (iris.hpp) on the fitted head: not part of
// the dissertation's fit (§4.1 fits the face only). Each eye's direction
// runs from its eyeball's centre (eyeballs.hpp) to the point where the
// camera ray through the iris centre meets the sphere of the iris ring's
// centres about it (radius iris_depth; its point nearest the ray where the
// ray passes beside it). Directions and angles are
// head-relative, in the model frame (eyeballs.hpp).

#include <array>
#include <functional>
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

// Beyond what eyes do, so taken for a wrong iris (a dark gap between the
// fingers of a hand over the eye, a lash line) or a wrong head pose:
// - an eye turned more than this from its rest axis (people turn their heads
//   long before their eyes reach 45 degrees; on the clips of ../shared/data,
//   with the rule below, it drops none of the 4,640 eyes of the clips where
//   the face is clear, and 47 of 584 on `emotions_pexels`, whose hands cover
//   her eyes);
inline constexpr double kMaxEyeTurnDeg = 45.0;
// - the farther turned of two eyes that disagree by more than this (the
//   eyes' lines of sight converge by a few degrees on a near point; on the
//   clear clips the two eyes' directions differ by at most 28 degrees, by a
//   median of 2.5-16).
inline constexpr double kMaxEyeDisagreementDeg = 30.0;

// The gaze of each eye with an iris, less the implausible ones (above).
GazeEstimate estimate_gaze(const EyeballGeometry& eyes, const HeadPose& pose, const PinholeCamera& camera,
                           const IrisCentres& iris);

IrisCentres iris_centres(const IrisPair& irises);

// How an 11.7 mm iris looks in each eye of a head at `pose` looking ahead:
// its radius in pixels (0 for an eye behind the camera), and how much
// narrower than tall it is: the cosine of the horizontal angle between the
// eye's axis and its line of sight to the camera.
std::array<IrisExpectation, 2> expected_irises(const EyeballGeometry& eyes, const HeadPose& pose,
                                               const PinholeCamera& camera);

// One frame's iris search, given each eye's expectation (expected_irises;
// an eye of radius 0 is not searched): the tracker calls it once it has a
// starting pose for the frame.
using IrisSearch = std::function<IrisPair(const std::array<IrisExpectation, 2>& expected)>;
// locate_iris in each eye of `grey` (8-bit) inside the detector's landmarks.
// It keeps a copy of the eyes' part of `grey` (eye_crop), not the image.
IrisSearch iris_search(const cv::Mat& grey, const Landmarks& observed);

}  // namespace facecap
