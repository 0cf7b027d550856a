#pragma once
// 68 facial landmarks in the iBUG 300-W order, image pixels (0-based, pixel
// centres at integer coordinates).
#include <array>
#include <filesystem>
#include <span>
#include <vector>

#include "facecap/core/geometry.hpp"

namespace facecap {

inline constexpr int kNumLandmarks = 68;
using Landmarks = std::array<Vec2f, kNumLandmarks>;
// All 68 at the origin. `Landmarks lm{}` does not zero them: Eigen's default
// constructor leaves a vector's coefficients uninitialised.
inline Landmarks zero_landmarks() {
  Landmarks lm;
  lm.fill(Vec2f::Zero());
  return lm;
}

// Each eye's six landmarks begin here: eye 0 (the subject's right, on the
// image's left for a face seen from the front) at iBUG 36, eye 1 at 42;
// each runs from a corner along the upper lid to the other corner and back
// along the lower lid (36 and 45 are the outer corners).
inline constexpr int kEyeLandmarks = 6;
inline constexpr int first_eye_landmark(int eye) { return 36 + kEyeLandmarks * eye; }

// Axis-aligned box in pixels.
struct Box {
  float x = 0, y = 0, width = 0, height = 0;
  float area() const { return width * height; }
  Vec2f center() const { return {x + 0.5f * width, y + 0.5f * height}; }
};

// The box around some points (a range of landmarks), or around all 68.
Box bounding_box(std::span<const Vec2f> points);
inline Box bounding_box(const Landmarks& lm) { return bounding_box(std::span<const Vec2f>(lm)); }

// Distance between the outer eye corners (iBUG 36 and 45): the normaliser of NME.
float outer_eye_distance(const Landmarks& lm);

// Mean point-to-point error of `estimate` against `truth`, divided by the
// truth's outer-eye-corner distance (the 300-W "NME, inter-ocular").
float landmark_nme(const Landmarks& estimate, const Landmarks& truth);

// Reads an iBUG .pts file (1-based coordinates, converted to 0-based).
// Throws facecap::Error naming the file when it is missing or malformed.
Landmarks read_pts(const std::filesystem::path& path);

}  // namespace facecap
