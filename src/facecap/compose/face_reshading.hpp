#pragma once
// Re-renders a face with new geometry (§5.3.3) from the source frame's own
// appearance: each pixel of the new surface takes the colour of the same
// surface point in the source frame, scaled by the ratio of the SH shading
// of the new and the old normal (I_new = I_old * s_new / s_old: the albedo
// cancels). The paper re-renders from the recovered albedo; at the coarse
// mesh's resolution that would blur skin texture that the source frame has.
// Where the frame saw the new surface edge-on or not at all (a closing lid
// unfolds), its colour comes from the skin around it (surface_exposure.hpp).
#include <opencv2/core.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

// The shading ratio s_new / s_old (clamped to 0.5-2; 1 where s_old is
// below 0.05) that scales a pixel's colour, taken only in part where the
// surface is near edge-on to the camera, before or after (`facing`: the
// lesser of the normals' components towards the viewer): there a degree of
// normal error changes the shading most, and the frame's pixel mixes the
// surface with what lies behind it. From kFacing (66 degrees off the view)
// in full, towards kGrazingFacing (84 degrees) as ratio^trust, trust
// falling smoothly to 0. Without it, the outer edge of a nose wing lowered
// by `--from happiness --to neutral` on emotions_pexels (frame 330; old and
// new facing 0.1-0.3, ratio 1.4-2) became a line of bright pixels, like a
// nose ring.
constexpr float kFacing = 0.4f;
constexpr float kGrazingFacing = 0.1f;
float shading_ratio(float s_old, float s_new, float facing);

// The layer spans the new face's image bounding box grown by `margin` pixels.
FaceLayer reshade_face(const cv::Mat& source, const Positions& old_points, const Positions& new_points,
                       const std::vector<Triangle>& triangles, const ShCoeffs& lighting, const PinholeCamera& camera,
                       int margin = 32);

// The image positions of some of the points (by index).
std::vector<cv::Point2f> project_vertices(const Positions& points, const std::vector<int>& vertices,
                                          const PinholeCamera& camera);

// The image bounding box of the points' projections.
cv::Rect projected_bounds(const Positions& points, const PinholeCamera& camera);

}  // namespace facecap
