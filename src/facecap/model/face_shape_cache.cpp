#include "facecap/model/face_shape_cache.hpp"

namespace facecap {

Positions FaceShapeCache::evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression) {
  const bool same = identity_shape_.size() > 0 && identity.size() == identity_.size() &&
                    (identity.array() == identity_.array()).all();
  if (!same) {
    identity_shape_ = model_.identity_shape(identity, region_);
    identity_ = identity;
  }
  return model_.with_expression(identity_shape_, expression, region_);
}

}  // namespace facecap
