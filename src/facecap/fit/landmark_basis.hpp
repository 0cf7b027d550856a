#pragma once
// The rows of the face model the coarse fit needs: the 68 landmark vertices
// and every jaw march-line vertex, gathered once (double precision) so that
// a landmark's model position X = n + B_id a + B_exp w costs a few hundred
// multiply-adds instead of a face-region evaluation.
#include <vector>

#include <Eigen/Core>

#include "facecap/core/camera.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/jaw_contour.hpp"

namespace facecap {

struct LandmarkBasis {
  std::vector<int> vertices;        // global vertex index of each gathered row triple
  std::vector<int> slot_of_vertex;  // global vertex -> slot, -1 where not gathered
  Eigen::Matrix3Xd neutral;         // 3 x slots
  Eigen::MatrixXd identity;         // 3*slots x identity modes
  Eigen::MatrixXd expression;       // 3*slots x expressions
  // The same rows slot by slot, each slot's 3 x modes block contiguous (at
  // columns [s modes, (s + 1) modes)): position() reads one vertex's rows
  // from a few cache lines rather than one line per mode.
  Eigen::MatrixXd identity_by_slot,
      expression_by_slot;  // 3 rows (dynamic, as identity and expression: the same products)
  JawContour contour;

  // Throws std::out_of_range for a vertex that was not gathered.
  int slot(int vertex) const;
  // Model-space position of a gathered vertex.
  Eigen::Vector3d position(int slot, const Eigen::VectorXd& identity_weights,
                           const Eigen::VectorXd& expression_weights) const;
};

LandmarkBasis gather_landmark_basis(const FaceModel& model, int identity_modes);

// The model point a landmark corresponds to: vertex a, or the point
// (1 - t) a + t b on a segment of the jaw outline.
struct Correspondence {
  int a = 0;
  int b = 0;
  double t = 0.0;
};
using Correspondences = std::array<Correspondence, 68>;
// The model's 68 landmark points (Correspondences' points) in camera space:
// centimetres, x right, y down, z forward (core/camera.hpp).
using LandmarkPoints = std::array<Vec3d, kNumLandmarks>;
inline LandmarkPoints zero_landmark_points() {
  LandmarkPoints p;
  p.fill(Vec3d::Zero());
  return p;
}

// Correspondences for a pose and shape: the landmark map's vertices, and for
// the jaw landmarks (0-7, 9-16) either (slide) the nearest point of the
// projected outline of their side to the observed landmark, searched near the
// landmark's place along the jaw so that the order is kept, or (march) the
// silhouette vertex of their jawline candidate (jaw_contour.hpp).
Correspondences pose_correspondences(const FaceModel& model, const LandmarkBasis& basis,
                                     const Eigen::VectorXd& identity, const Eigen::VectorXd& expression,
                                     const HeadPose& pose, const PinholeCamera& camera, const Landmarks& observed,
                                     bool slide = true);

}  // namespace facecap
