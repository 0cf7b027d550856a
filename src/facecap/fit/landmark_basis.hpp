#pragma once
// The rows of the face model the coarse fit needs: the 68 landmark vertices
// and every jaw march-line vertex, gathered once (double precision) so that
// a landmark's model position X = n + B_id a + B_exp w costs a few hundred
// multiply-adds instead of a face-region evaluation.
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "facecap/core/camera.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/jaw_contour.hpp"

namespace facecap {

struct LandmarkBasis {
  std::vector<int> vertices;             // global vertex index of each gathered row triple
  std::unordered_map<int, int> slot_of;  // global vertex -> slot
  Eigen::Matrix3Xd neutral;              // 3 x slots
  Eigen::MatrixXd identity;              // 3*slots x identity modes
  Eigen::MatrixXd expression;            // 3*slots x expressions
  JawContour contour;

  int slot(int vertex) const { return slot_of.at(vertex); }
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
