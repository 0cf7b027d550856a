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
// The values are LiveLinkFace's (livelink_face.hpp: how the model's weights
// map onto the shapes); the app's columns order them a few apart from its
// stream (JawRight before JawLeft, MouthRight before MouthLeft).
#include <string>
#include <vector>

#include "facecap/io/livelink_face.hpp"

namespace facecap {

class LiveLinkCsv {
 public:
  // `fps`: the timecode's rate.
  explicit LiveLinkCsv(double fps);

  std::string header() const;
  std::string row(double seconds, const LiveLinkFace::Values& values) const;
  // HH:MM:SS:FF.fff at `fps` frames a second.
  static std::string timecode(double seconds, double fps);

  // The app's 61 value columns, in its order.
  static const std::vector<std::string>& columns();

 private:
  std::vector<int> order_;  // for each column, its value's index in LiveLinkFace::names()
  double fps_;
};

}  // namespace facecap
