#pragma once
// Renders the frames of a synthetic performance and the landmarks a perfect
// detector would mark on them.
#include <memory>
#include <random>

#include <opencv2/core.hpp>

#include "facecap/core/midpoint_subdivision.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/model/eyeballs.hpp"
#include "facecap/model/jaw_contour.hpp"
#include "facecap/render/rasterizer.hpp"
#include "facecap/synth/performance.hpp"
#include "facecap/synth/skin_albedo.hpp"

namespace facecap {

class SynthRenderer {
 public:
  SynthRenderer(const FaceModel& model, const SynthPerformance& performance);

  // The frame as an 8-bit BGR image (supersampled 2x, with sensor noise).
  cv::Mat render(const SynthFrame& frame, std::mt19937_64& noise_rng) const;

  // The 68 landmarks as a detector would mark them: fixed vertices, with the
  // jaw on the silhouette for the frame's pose (jaw_contour.hpp).
  Landmarks landmarks(const SynthFrame& frame) const;
  // The 68 landmark-map vertices projected, with no silhouette correction.
  Landmarks landmark_vertex_projections(const SynthFrame& frame) const;

  // Where the centre of the iris of eye 0 (the subject's right) or 1
  // projects: what a perfect iris detector would find. The centre of the
  // painted ring, which lies on the eye's axis but nearer the eyeball's
  // centre than EyeballGeometry::iris_depth's sphere puts it: ICT's cornea
  // bulges (painted_iris_depth).
  Vec2d iris_centre(const SynthFrame& frame, int eye) const;
  // Distance from each eyeball's centre, along its axis, to the plane of
  // the painted iris's rim on this identity's eyeball (cm).
  double painted_iris_depth(int eye) const { return painted_iris_depth_[eye]; }
  const EyeballGeometry& eyeballs() const { return eyes_; }

  const SynthAppearance& appearance() const { return appearance_; }
  // Displacement (cm) of each fine face vertex; empty without detail.
  const MidpointSubdivision* detail_mesh() const { return detail_ ? &subdivision_ : nullptr; }
  const std::vector<float>& detail_displacement() const { return displacement_; }
  // Camera-space positions of the detailed face surface for a frame (3 x fine vertices).
  Positions detailed_face(const SynthFrame& frame) const;

 private:
  Positions head_positions(const SynthFrame& frame) const;

  const FaceModel& model_;
  const SynthPerformance& performance_;
  SynthAppearance appearance_;
  JawContour contour_;
  EyeballGeometry eyes_;
  std::array<double, 2> painted_iris_depth_{0.0, 0.0};
  std::vector<Triangle> head_triangles_;  // non-face regions, global indices
  std::vector<Triangle> face_triangles_;  // face region, local = global indices
  bool detail_ = false;
  MidpointSubdivision subdivision_;
  std::vector<float> displacement_;
  Positions fine_albedo_;
  cv::Mat background_;  // BGR CV_32FC3 at render resolution
  static constexpr int kSupersample = 2;
};

}  // namespace facecap
