#pragma once
// Faces at any roll: the frame searched by dlib's detector in views turned
// by multiples of 45 degrees (UprightView), each face found once, in the view
// where the detector was surest of it. The tracker's search for a face lost
// in its own view, the roster of --all-faces and `probe` use it.
#include <array>
#include <span>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/upright_view.hpp"

namespace facecap {

// The turns searched, nearest upright first: a face rolled up to 180 degrees
// either way lies within 22.5 of one of them.
inline constexpr std::array<float, 8> kFaceTurns = {0, 45, -45, 90, -90, 135, -135, 180};

// Halfway between them: the detector reaches a face about 15 degrees from
// upright only where it is near frontal; one rolled 60 degrees and turned 30
// degrees away (a synthetic render) is found in none of kFaceTurns, and 7.5
// degrees from -67.5. Searched where a shot's first search of kFaceTurns
// finds nothing (find_first_turned_faces).
inline constexpr std::array<float, 8> kFaceHalfTurns = {22.5, -22.5, 67.5, -67.5, 112.5, -112.5, 157.5, -157.5};

struct TurnedFace {
  float degrees = 0;      // the view's turn (about the face's roll in the frame)
  FaceDetection in_view;  // its box in that view, at the frame's scale
  FaceDetection shown;    // the same box, centred where the frame shows the face
};

// Each face `detector` finds in `grey` turned by one of `turns`, every view
// scaled so that its longer side is at most `max_side` (0: full size). A face
// found in two turns (its centres within a quarter of its box's width plus
// height) is kept from the view with the higher score. `ms`, where given,
// gets the time added.
std::vector<TurnedFace> find_turned_faces(const FaceDetector& detector, const cv::Mat& grey,
                                          std::span<const float> turns, int max_side, double* ms = nullptr);

// A shot's first search off upright, where upright showed no face: the faces
// of find_turned_faces in `turns`, or where none of those shows one, in
// kFaceHalfTurns. (Searched beside the turns instead, the half turns gave the
// LFPW portrait turned 60 degrees an upside-down detection in the 112.5
// degree view that scored above the face's own.) The tracker, the roster of
// --all-faces and `probe` start a shot with it.
std::vector<TurnedFace> find_first_turned_faces(const FaceDetector& detector, const cv::Mat& grey,
                                                std::span<const float> turns, int max_side, double* ms = nullptr);

}  // namespace facecap
