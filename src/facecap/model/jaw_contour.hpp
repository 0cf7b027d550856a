#pragma once
// Pose-dependent correspondences for the 17 jaw landmarks (iBUG 0-16).
//
// A detector marks the jaw on the visible outline of the face, and which
// surface point forms that outline depends on the head pose. Each jawline
// candidate of FACTS.md owns a "march line": the face vertices at its
// height, from the candidate on the frontal silhouette toward the middle of
// the face. For a pose, the silhouette vertex of a line is the one that
// projects furthest outward (image left for the subject's right side, image
// right for the left): on the side turning away from the camera the outline
// moves inward along the line, as in 3DDFA's landmark marching.
//
// Two uses:
//  - silhouette_vertices(): one vertex per jaw landmark from the short lists
//    (the synthetic ground truth's definition of where a jaw landmark is);
//  - silhouette_path(): the outline as a polyline of the extended lists'
//    silhouette vertices, ear to chin, along which a detected jaw landmark
//    slides to its nearest point (as eos does for its contour), so that a
//    detector's spacing along the jaw does not matter, only its distance
//    across the outline.
#include <array>
#include <functional>
#include <vector>

#include "facecap/core/geometry.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap {

struct JawContour {
  // lines[k]: march line of jaw landmark k (k = 0..16) from the short lists;
  // lines[8] holds the chin vertex only.
  std::array<std::vector<int>, 17> lines;
  // March lines of the extended lists, ear to chin, for each side.
  std::vector<std::vector<int>> right_path;
  std::vector<std::vector<int>> left_path;
  int chin = -1;
};

// Builds the march lines from the model's neutral shape.
JawContour build_jaw_contour(const FaceModel& model);

// camera_position(vertex): the vertex in camera space for the current pose and shape.
using CameraPositionFn = std::function<Vec3d(int vertex)>;

// The image direction along which the jaw's silhouette is outermost, a
// unit vector. A march line runs along the head's left-right axis (model x
// under `model_to_camera`), and where it crosses the outline its image is
// outermost across the outline, which runs along the head's up axis. Within
// 15 degrees of one of the image's axes (a head upright, or on a camera on
// its side or upside down) that axis, as the fit was tuned with upright:
// with the head's own axis at every roll, the self-swaps of the real clips
// moved by -0.8 to +3.9 % (`eval swap --self`: emotions_pexels, whose head
// rolls up to 27 degrees, 11.11 -> 11.54; address_720p_b 7.51 -> 7.59) and
// the fit's NME on emotions_pexels rose 0.8 %. At 45 degrees from them the
// head's axis; the angle scaled in between. So a quarter turn of the camera
// turns the silhouette's choice with it, exactly.
Vec2d image_lateral(const Mat3d& model_to_camera);

// For each jaw landmark, the short-list line vertex on the silhouette;
// `lateral`: image_lateral() of the pose.
std::array<int, 17> silhouette_vertices(const JawContour& contour, const CameraPositionFn& camera_position,
                                        const Vec2d& lateral);

// The same for model-space face-region positions (column = global vertex
// index) under the rotation `model_to_camera` (R * F of camera.hpp) and translation.
std::array<int, 17> silhouette_vertices(const JawContour& contour, const Positions& face_positions,
                                        const Mat3d& model_to_camera, const Vec3d& translation);

// The outline of one side (right: iBUG 0-7, left: 9-16) as silhouette
// vertices from the ear down to the chin (the chin vertex last).
std::vector<int> silhouette_path(const JawContour& contour, bool right_side, const CameraPositionFn& camera_position,
                                 const Vec2d& lateral);

// The 68 correspondence vertices for a pose: the landmark map with the jaw
// landmarks replaced by their silhouette vertices (short lists).
std::array<int, 68> landmark_vertices_for_pose(const FaceModel& model, const JawContour& contour,
                                               const Positions& face_positions, const Mat3d& model_to_camera,
                                               const Vec3d& translation);

}  // namespace facecap
