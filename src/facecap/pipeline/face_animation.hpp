#pragma once
// A tracked video as one animated glTF (`facecap track --gltf`): the face
// region of the ICT model with the video's identity as its rest shape, and
// behind its holes the mouth, teeth, tongue and eyeballs (a second part,
// coloured per vertex), the 53 expression blend shapes as morph targets under
// their ARKit names, four more that turn both eyeballs by kEyeTurnTargetDeg
// left, right, up and down (ICT's eyeLook shapes move the lids only), one key
// per tracked frame (head pose, weights and gaze), and the fitted camera at
// the origin, so that looking through it reproduces the video's view. Lost
// frames have no key; players interpolate across them.
//
// The file also carries the face matte (face_matte.hpp) as an image named
// kFaceMatteImageName that no material uses: what of the face part a render
// over the footage shows (blender/import_facecap.py holds the rest out).
//
// Axes: glTF's world is the OpenCV camera frame turned half a turn about x
// (F = diag(1, -1, -1): y up, the camera looking down -z), in metres. With
// the pose's X_camera = R F X_model + t, the node carries rotation F R F and
// translation F t, and the mesh is in ICT model space (y up, z out of the
// face), which needs no change of axes.
#include <array>
#include <optional>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/fit/gaze.hpp"
#include "facecap/io/gltf_writer.hpp"
#include "facecap/model/face_model.hpp"

namespace facecap {

inline constexpr const char* kFaceMatteImageName = "face_matte";

struct FaceAnimationKey {
  double time = 0;  // seconds
  HeadPose pose;
  Eigen::VectorXf expression;     // the model's expression weights
  std::optional<Vec2d> gaze_deg;  // head-relative (yaw, pitch) (eyeballs.hpp); none: as the key before
};

// The eyeball turns after the expression targets: a turn of kEyeTurnTargetDeg
// each, weighted by angle / kEyeTurnTargetDeg. A blend of position offsets
// moves points along chords, not arcs (at half a turn the pupil sits
// r (1 - cos(kEyeTurnTargetDeg / 2)) = 0.4 mm inside the eyeball), and the
// yaw and pitch offsets add where turns would compose: played back, a gaze of
// (20, -12) degrees points 1.1-1.2 degrees off (face_animation_test).
inline constexpr double kEyeTurnTargetDeg = 30.0;
inline const std::array<const char*, 4> kEyeTurnTargetNames = {"eyesTurnLeft", "eyesTurnRight", "eyesTurnUp",
                                                               "eyesTurnDown"};

// Appends the key of frame `index`. Images have no timeline (`timeline`
// false): they are keyed 1/30 s apart. A key no later than the last one (a
// video's repeated timestamp) is dropped, as glTF needs increasing times.
void append_animation_key(std::vector<FaceAnimationKey>& keys, bool timeline, int index, double time,
                          const HeadPose& pose, const Eigen::VectorXf& expression,
                          std::optional<Vec2d> gaze_deg = std::nullopt);
// A measured gaze's angles, or none (gaze.hpp's estimate holds no eye).
std::optional<Vec2d> key_gaze(const GazeEstimate& gaze);

struct FaceAnimationCamera {
  double focal_px = 0;
  int width = 0, height = 0;
};

// The mesh at rest: every model vertex in model space (3N values, cm), and
// the factor the expression blend shapes are scaled by. A face scaled about
// its centre (the swap's size match, swap/size_match.hpp) moves each vertex's
// blend-shape offsets by the same factor.
struct FaceAnimationRest {
  Eigen::VectorXf head;
  float blend_shape_scale = 1.0f;
};

// neutral + B_id identity over the whole head. `identity`: the leading
// identity modes (as IdentityEstimate holds them).
FaceAnimationRest identity_rest(const FaceModel& model, const Eigen::VectorXf& identity);

// The face part is split where the UV layout has seams.
GltfAnimatedMesh face_animation(const FaceModel& model, const FaceAnimationRest& rest,
                                const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera);
// The same with the rest shape of a tracked identity.
GltfAnimatedMesh face_animation(const FaceModel& model, const Eigen::VectorXd& identity,
                                const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera);

// Per part of face_animation(), the model vertex each glTF vertex copies.
std::vector<std::vector<int>> face_animation_source_vertices(const FaceModel& model);

}  // namespace facecap
