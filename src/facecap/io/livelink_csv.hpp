#pragma once
// A capture as a Live Link Face take CSV: the file Epic's iPhone app exports
// and that Unreal's Live Link Face importer (MetaHuman), and Blender and Maya
// add-ons, read onto a rig with ARKit's 52 blend shapes. Columns:
//   Timecode       HH:MM:SS:FF.fff (FF: the frame within the second at the
//                  input's rate, .fff: the part of a frame)
//   BlendShapeCount 61
//   the 52 ARKit shapes in the app's order (EyeBlinkLeft ... TongueOut)
//   HeadYaw, HeadPitch, HeadRoll, LeftEyeYaw, LeftEyePitch, LeftEyeRoll,
//   RightEyeYaw, RightEyePitch, RightEyeRoll: radians
// The ICT model's 53 weights map onto them by name: eyeBlink_L is
// EyeBlinkLeft, the shapes ICT splits that ARKit does not (browInnerUp,
// cheekPuff) are the mean of their halves, and TongueOut, which ICT lacks, is 0.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "facecap/core/geometry.hpp"

namespace facecap {

class LiveLinkCsv {
 public:
  // `expression_names`: the model's, in its order; `fps`: the timecode's rate.
  LiveLinkCsv(const std::vector<std::string>& expression_names, double fps);

  struct Pose {
    Vec3d head_yaw_pitch_roll_deg = Vec3d::Zero();  // yaw_pitch_roll_deg of the head's rotation
    Vec2d left_eye_deg = Vec2d::Zero();             // gaze (yaw, pitch) of the subject's left eye
    Vec2d right_eye_deg = Vec2d::Zero();
  };

  std::string header() const;
  std::string row(double seconds, const Eigen::VectorXf& weights, const Pose& pose) const;
  // HH:MM:SS:FF.fff at `fps` frames a second.
  static std::string timecode(double seconds, double fps);

  // The app's 52 shape names, in its column order.
  static const std::vector<std::string>& arkit_names();

 private:
  // For each ARKit shape, the model weights whose mean it is (none: 0).
  std::vector<std::vector<int>> sources_;
  double fps_;
};

}  // namespace facecap
