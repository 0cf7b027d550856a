#pragma once
// A procedural albedo for synthetic faces: skin painted in the ICT face UV
// layout (darker brows, lips, lid lines and nostrils, placed from the UVs of
// the landmark vertices) or taken from a given texture, plus flat colours
// for eyes, teeth and mouth.
#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/model/face_model.hpp"

namespace facecap {

struct SynthAppearance {
  cv::Mat face_texture;     // BGR, CV_32FC3 in [0, 1], face-region UV layout (v up)
  Positions vertex_albedo;  // 3 x num_vertices (whole head), RGB in [0, 1]
  std::vector<bool> drawn;  // which vertices belong to rendered regions (eye overlays are not)
  // Each eyeball's vertices painted as iris or pupil (eye 0: the subject's
  // right): a flat disc behind the cornea in a real eye, which the renderer
  // shades with the eye's axis as their normal.
  std::array<std::vector<int>, 2> iris_vertices;
};

// `face_texture` (SynthOptions::face_texture), when given, is the face's
// skin instead of the painted one, and its mean colour over the face that of
// the rest of the head; `painted_tone_rgb` then goes unused.
SynthAppearance paint_appearance(const FaceModel& model, const Vec3f& painted_tone_rgb, uint64_t seed,
                                 int texture_size = 1024, const cv::Mat& face_texture = {});

}  // namespace facecap
