#pragma once
// Bakes a per-vertex attribute into a texture in UV space (the mesh's
// per-corner UVs), e.g. the recovered albedo as `albedo.png` for the ICT UV
// layout, ready for Blender or three.js.
#include <opencv2/core.hpp>

#include "facecap/core/mesh.hpp"

namespace facecap {

// values: 3 x N RGB in [0, 1]. Returns a BGR 8-bit image of size x size;
// texels no triangle covers stay black; a 2-texel dilation hides seams.
cv::Mat bake_uv_texture(const TriangleMesh& mesh, const Positions& values, int size = 1024);

}  // namespace facecap
