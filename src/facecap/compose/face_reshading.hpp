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
