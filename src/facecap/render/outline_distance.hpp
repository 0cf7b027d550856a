#pragma once
// How far each drawn pixel of a render lies inside its outer outline: the
// Euclidean distance (pixels) to the nearest undrawn pixel that connects to
// the buffers' border. Undrawn pixels enclosed by the render (the eye and
// mouth openings of a face, a gap between its triangles) count as drawn, so
// only the outline against the scene behind the render is measured. CV_32F,
// the buffers' size; 0 on the undrawn pixels outside.
#include <opencv2/core.hpp>

#include "facecap/render/rasterizer.hpp"

namespace facecap {

cv::Mat outline_distance(const RasterBuffers& buffers);

}  // namespace facecap
