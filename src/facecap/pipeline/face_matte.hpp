#pragma once
// The face matte (`track --gltf` / `--uv-pass`: DIR/face_matte.png): which
// part of the tracked face region a render of it should show over the
// footage. The face region runs from the scalp to the neck, ears' front
// included, and the footage's own hair, ears, neck and collar sit where it
// does; the matte keeps the narrow face of FACTS.md (brows to chin, cheek to
// cheek), with its outer edge feathered, and leaves the rest to the footage.
// It is an 8-bit grey image in the ICT UV layout of albedo.png, texture.png
// and the detail maps: 255 where the face shows, 0 where the footage does.
// blender/import_facecap.py holds out the face's material by it; through a
// UV pass (Nuke's STMap) it is a matte in the frame.
#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace facecap {

struct FaceModel;

// How far in from the narrow face's outer edge the matte reaches 1.
inline constexpr float kFaceMatteFeatherMm = 8.0f;

// Per vertex of the face region (regions::kFace): 0 off the narrow face; on
// it, smoothstep(d / feather_mm) of its distance d along the mesh's edges,
// on the model's mean face, to the nearest vertex off it. The narrow face's
// holes (the eyes, the mouth) open onto the eyes and the mouth socket, not
// onto the footage, so they are no edge: the lips and eyelids keep 1.
Eigen::VectorXf narrow_face_matte(const FaceModel& model, float feather_mm = kFaceMatteFeatherMm);

// That matte baked into the UV layout, size x size, 8-bit grey (the islands
// grown by 2 texels, as albedo.png's are).
cv::Mat face_matte_image(const FaceModel& model, int size = 1024, float feather_mm = kFaceMatteFeatherMm);

}  // namespace facecap
