#pragma once
// Pose-dependent correspondences for the 17 jaw landmarks (iBUG 0-16).
//
// A detector marks the jaw on the visible outline of the face, and which
// surface point forms that outline depends on the head pose. Each jaw
// landmark k (except the chin, 8) owns a "march line": the face vertices at
// the height of its jawline candidate (FACTS.md), running from the candidate
// on the frontal silhouette toward the middle of the face. For a given pose,
// the landmark corresponds to the vertex of its line that projects furthest
// outward (image left for the subject's right side, image right for the left):
// on the side turning away from the camera the outline moves inward along the
// line, as eos and 3DDFA's landmark marching do.
#include <array>
#include <functional>
#include <vector>

#include "facecap/core/geometry.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap {

struct JawContour {
  // lines[k]: candidate vertices of jaw landmark k (k = 0..16), global
  // vertex indices into the face region; lines[8] holds the chin vertex only.
  std::array<std::vector<int>, 17> lines;
};

// Builds the march lines from the model's neutral shape.
JawContour build_jaw_contour(const FaceModel& model);

// For each jaw landmark, the line vertex on the silhouette: the one whose
// camera-space position (given by `camera_position(vertex)`) projects
// furthest outward. Returns 17 vertex indices.
std::array<int, 17> silhouette_vertices(const JawContour& contour,
                                        const std::function<Vec3d(int vertex)>& camera_position);

// The same for model-space face-region positions (column = global vertex
// index) under the rotation `model_to_camera` (R * F of camera.hpp) and translation.
std::array<int, 17> silhouette_vertices(const JawContour& contour, const Positions& face_positions,
                                        const Mat3d& model_to_camera, const Vec3d& translation);

// The 68 correspondence vertices for a pose: the landmark map with the jaw
// landmarks replaced by their silhouette vertices.
std::array<int, 68> landmark_vertices_for_pose(const FaceModel& model, const JawContour& contour,
                                               const Positions& face_positions, const Mat3d& model_to_camera,
                                               const Vec3d& translation);

}  // namespace facecap
