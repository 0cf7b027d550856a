#pragma once
// A region's positions for frame after frame of one face. The identity part,
// neutral + B_id a (100 modes), is the same for every frame of a shot: it is
// evaluated when the identity changes, and each frame adds only its
// expression weights (53 modes), a third of the work of FaceModel::evaluate.
#include <Eigen/Core>

#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"

namespace facecap {

class FaceShapeCache {
 public:
  FaceShapeCache(const FaceModel& model, const Region& region) : model_(model), region_(region) {}

  // FaceModel::evaluate(identity, expression, region), bit for bit.
  Positions evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression);

 private:
  const FaceModel& model_;
  Region region_;
  Eigen::VectorXf identity_;        // of the cached shape
  Eigen::VectorXf identity_shape_;  // empty until the first call
};

}  // namespace facecap
