#include "facecap/model/face_shape_cache.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace facecap {

TEST(FaceShapeCache, GivesWhatEvaluateGivesAndFollowsAChangedIdentity) {
  FACECAP_REQUIRE_MODEL(model);
  FaceShapeCache cache(*model, regions::kFace);
  const Eigen::VectorXf first = Eigen::VectorXf::Random(model->num_identity());
  Eigen::VectorXf second = first;
  second[3] += 0.5f;  // one mode changed: a new shot's identity
  const Eigen::VectorXf identities[] = {first, first, second, second, first};
  for (const Eigen::VectorXf& identity : identities) {
    const Eigen::VectorXf expression =
        (Eigen::VectorXf::Random(model->num_expressions()).array() * 0.5f + 0.5f).matrix();
    const Positions cached = cache.evaluate(identity, expression);
    const Positions direct = model->evaluate(identity, expression, regions::kFace);
    ASSERT_EQ(cached.cols(), direct.cols());
    EXPECT_EQ((cached - direct).cwiseAbs().maxCoeff(), 0.0f);  // bit for bit
  }
}

}  // namespace facecap
