#pragma once
// A procedural albedo for synthetic faces: skin painted in the ICT face UV
// layout (darker brows, lips, lid lines and nostrils, placed from the UVs of
// the landmark vertices), plus flat colours for eyes, teeth and mouth.
#include <cstdint>

#include <opencv2/core.hpp>

#include "facecap/model/face_model.hpp"

namespace facecap {

struct SynthAppearance {
  cv::Mat face_texture;     // BGR, CV_32FC3 in [0, 1], face-region UV layout (v up)
  Positions vertex_albedo;  // 3 x num_vertices (whole head), RGB in [0, 1]
  std::vector<bool> drawn;  // which vertices belong to rendered regions (eye overlays are not)
};

SynthAppearance paint_appearance(const FaceModel& model, const Vec3f& skin_tone_rgb, uint64_t seed,
                                 int texture_size = 1024);

}  // namespace facecap
