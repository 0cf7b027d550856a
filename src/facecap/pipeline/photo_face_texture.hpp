#pragma once
// A real portrait's skin as a texture for synthetic renders
// (SynthOptions::face_texture): renders with known shape, pose, expression
// and lighting that carry a real face's brows, lids, lips and skin, which a
// landmark detector trained on photos sees as it sees photos.
#include <string>

#include <opencv2/core.hpp>

#include "facecap/model/face_model.hpp"

namespace facecap {

// The portrait is reconstructed as a swap's source is (reconstruct_source:
// its largest face), unshaded by its fitted lighting into the ICT face UV
// layout, completed from its mirror image where it was seen obliquely, and
// filled where it was not seen at all (the eye and mouth openings, the
// sides of the head). Returns BGR CV_32FC3 in [0, 1], `size` x `size`.
// Throws facecap::Error naming the photo when it cannot be read or holds no
// face.
cv::Mat face_texture_from_photo(const FaceModel& model, const std::string& photo, int size = 1024, bool quiet = true);

}  // namespace facecap
