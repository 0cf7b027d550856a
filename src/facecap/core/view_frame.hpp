#pragma once
// The y-up view frame that glTF, Blender and Nuke cameras (and facecap's
// shading) use: the OpenCV camera frame of camera.hpp turned half a turn
// about x, F = diag(1, -1, -1): x right, y up, the camera at the origin
// looking down -z.
#include "facecap/core/camera.hpp"

namespace facecap {

// A head pose in that frame: X_view = rotation X_model + translation, with
// rotation F R F (the model's own axes are y up already) and translation F t.
struct ViewPose {
  Mat3d rotation;
  Vec3d translation;
};

inline ViewPose pose_in_view_frame(const HeadPose& pose) {
  const Mat3d flip = Vec3d(1, -1, -1).asDiagonal();
  return {flip * pose.model_to_camera_rotation(), flip * pose.translation};
}

}  // namespace facecap
