#pragma once
// A real face's skin as a texture in the ICT face UV layout: for synthetic
// renders (SynthOptions::face_texture: renders with known shape, pose,
// expression and lighting that carry a real face's brows, lids, lips and
// skin, which a landmark detector trained on photos sees as it sees photos)
// and for `track --texture`.
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/spherical_harmonics.hpp"
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

// The lighting of a frame's fitted face alone: the refinement's lighting
// estimate on the coarse face (`points`: the face region in camera space),
// its albedo fixed from this one frame, as a swap's source photo is lit.
ShCoeffs face_lighting_of_frame(const FaceModel& model, const cv::Mat& image, const Positions& points,
                                const PinholeCamera& camera);

// A frame's fitted face unshaded by `lighting` into the ICT face UV layout
// (as face_texture_from_photo). BGR CV_32FC3 in [0, 1], `size` x `size`.
cv::Mat face_texture_of_frame(const FaceModel& model, const cv::Mat& image, const Positions& points,
                              const PinholeCamera& camera, const ShCoeffs& lighting, int size = 1024);

// The skin texture of a face gathered over its first frames (`track
// --texture`): each frame unshaded by its lighting (a lighting-only
// refinement's over these frames, so that their albedo scale is one) with
// the eyes, the mouth and what is off the skin's colour left out, weighed by
// how squarely each texel was seen; their weighted mean completed from its
// mirror image and filled, as a photo's is. One frame gives
// face_texture_of_frame's texture.
class FaceTextureGatherer {
 public:
  FaceTextureGatherer(const FaceModel& model, int frames, int size = 1024);
  ~FaceTextureGatherer();
  FaceTextureGatherer(FaceTextureGatherer&&) noexcept;
  FaceTextureGatherer& operator=(FaceTextureGatherer&&) noexcept;

  bool wants_more() const;
  // A frame with its fitted face (`points`: the face region in camera space).
  void add(const cv::Mat& image, const Positions& points, const PinholeCamera& camera);
  bool empty() const;
  // BGR CV_32FC3 in [0, 1]; empty before the first frame.
  cv::Mat texture() const;
  // Starts again (another shot: another face, another light).
  void clear();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
