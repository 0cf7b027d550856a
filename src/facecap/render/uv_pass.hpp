#pragma once
// A UV pass (an ST map) of a mesh seen through a camera: each pixel the UV of
// the surface point it shows, so that a compositor warps a texture painted in
// the mesh's UV layout onto the frame (Nuke's STMap node; a UV pass in
// Fusion, After Effects' RE:Map, Blender's compositor).
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

// `mesh` (with UVs) at `camera_points` (camera space, cm) through `camera`,
// in an image of `size`: CV_16UC4 in OpenCV's BGRA order, red u and green v
// (u right, v up, as in OBJ; 65535 is 1), blue 0, alpha 65535 where the mesh
// covers the pixel's centre (front faces, nearest first) and everything 0
// elsewhere. `buffers` is scratch, kept between calls.
cv::Mat uv_pass(const TriangleMesh& mesh, const Positions& camera_points, const PinholeCamera& camera, cv::Size size,
                RasterBuffers& buffers);

}  // namespace facecap
