#pragma once
// `track --landmarks-csv`: DIR/landmarks.csv, each frame's 68 landmarks (iBUG
// order) in the columns of OpenFace's tables, so that scripts written for
// OpenFace read ours:
//   frame, time, status,
//   x_0..x_67, y_0..y_67          the detector's landmarks (pixels)
//   fit_x_0..fit_x_67, fit_y_...  the fitted model's, projected (pixels)
//   X_0..X_67, Y_0..Y_67, Z_0..   the fitted model's in camera space
//                                 (millimetres; x right, y down, z forward,
//                                 as OpenFace's)
// The jaw's model points slide along the jawline with the pose (§4.1): they
// are where the face's outline is in that frame, not fixed vertices. A frame
// without a face has its fields empty.
#include <string>

#include "facecap/fit/coarse_tracker.hpp"

namespace facecap {

std::string landmark_table_header();
// A frame's row, without its newline; `fit` null for a frame without a face.
std::string landmark_table_row(int frame, double time, const std::string& status, const CoarseFit* fit);

}  // namespace facecap
