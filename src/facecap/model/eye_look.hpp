#pragma once
// The eight eyeLook weights (ARKit's eyeLookIn/Out/Up/Down, per eye) of a gaze.
//
// ICT's eyeLook shapes move the lids the way a gaze does but leave the
// eyeballs where they are (eyeballs.hpp), and ARKit-style rigs read these
// weights as where the eyes look. facecap's convention ties the two: both
// eyes turned alike by (yaw, pitch) degrees (eyeballs.hpp: yaw > 0 toward the
// subject's left, pitch > 0 up) weigh their shapes by the angle over
// kEyeLookFullDeg, clamped to [0, 1]:
//  - yaw > 0: eyeLookOut_L (the left eye turns outward) and eyeLookIn_R;
//  - yaw < 0: eyeLookIn_L and eyeLookOut_R;
//  - pitch > 0: eyeLookUp_L and _R; pitch < 0: eyeLookDown_L and _R;
// and the opposite shapes 0. At 1, ICT's lids show a gaze of about this
// much: eyeLookDown lowers the upper lid 7.7 mm (the iris's top moves about
// 7 mm on a 12 mm eyeball turned 35 degrees), eyeLookIn/Out shift the lids
// 2.5 mm; it is also the turn of the glTF's eyesTurn targets (gltf_writer.hpp).
#include <array>
#include <utility>
#include <vector>

#include "facecap/model/face_model.hpp"

namespace facecap {

inline constexpr double kEyeLookFullDeg = 30.0;

class EyeLookShapes {
 public:
  explicit EyeLookShapes(const FaceModel& model);

  // (expression index, weight) of each eyeLook shape the model has, for a
  // gaze (yaw, pitch) in degrees.
  std::vector<std::pair<int, double>> weights(const Vec2d& gaze_deg) const;
  // The expression indices of the eyeLook shapes the model has.
  std::vector<int> indices() const;

 private:
  // Out_L, In_R, In_L, Out_R, Up_L, Up_R, Down_L, Down_R; -1 where absent.
  std::array<int, 8> index_{};
};

}  // namespace facecap
