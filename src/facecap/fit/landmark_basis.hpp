#pragma once
// The rows of the face model the coarse fit needs: the 68 landmark vertices
// and every jaw march-line vertex, gathered once (double precision) so that
// a landmark's model position X = n + B_id a + B_exp w costs a few hundred
// multiply-adds instead of a face-region evaluation.
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "facecap/model/face_model.hpp"
#include "facecap/model/jaw_contour.hpp"

namespace facecap {

struct LandmarkBasis {
  std::vector<int> vertices;              // global vertex index of each gathered row triple
  std::unordered_map<int, int> slot_of;   // global vertex -> slot
  Eigen::Matrix3Xd neutral;               // 3 x slots
  Eigen::MatrixXd identity;               // 3*slots x identity modes
  Eigen::MatrixXd expression;             // 3*slots x expressions
  JawContour contour;

  int slot(int vertex) const { return slot_of.at(vertex); }
  // Model-space position of a gathered vertex.
  Eigen::Vector3d position(int slot, const Eigen::VectorXd& identity_weights, const Eigen::VectorXd& expression_weights) const;
};

LandmarkBasis gather_landmark_basis(const FaceModel& model, int identity_modes);

// The 68 correspondence vertices for a pose (jaw on the silhouette), as
// jaw_contour.hpp defines them, computed from the gathered rows.
std::array<int, 68> pose_correspondences(const FaceModel& model, const LandmarkBasis& basis,
                                         const Eigen::VectorXd& identity, const Eigen::VectorXd& expression,
                                         const Mat3d& model_to_camera, const Vec3d& translation);

}  // namespace facecap
