#include "facecap/model/face_model.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(FaceModel, EvaluatesTheLinearModel) {
  FACECAP_REQUIRE_MODEL(model);
  Eigen::VectorXf a = Eigen::VectorXf::Zero(model->num_identity());
  Eigen::VectorXf b = Eigen::VectorXf::Zero(model->num_expressions());
  a[0] = 1.5f;
  a[7] = -0.5f;
  b[model->expression_index("jawOpen")] = 0.6f;
  const Positions full = model->evaluate(a, b);
  const int v = 5518;  // lower lip
  const Vec3f expected =
      Vec3f(model->neutral.segment<3>(3 * v)) + 1.5f * Vec3f(model->identity_basis.col(0).segment<3>(3 * v)) -
      0.5f * Vec3f(model->identity_basis.col(7).segment<3>(3 * v)) +
      0.6f * Vec3f(model->expression_basis.col(model->expression_index("jawOpen")).segment<3>(3 * v));
  EXPECT_NEAR((full.col(v) - expected).norm(), 0.0f, 1e-5f);
  // jawOpen moves the lower lip down by centimetres.
  EXPECT_LT(full(1, v), model->neutral[3 * v + 1] - 1.0f);
}

TEST(FaceModel, RegionEvaluationMatchesTheFullHead) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXf a = Eigen::VectorXf::Random(50);  // shorter vectors use the leading modes
  const Eigen::VectorXf b = (Eigen::VectorXf::Random(53).array() * 0.5f + 0.5f).matrix();
  const Positions full = model->evaluate(a, b);
  const Positions face = model->evaluate(a, b, regions::kFace);
  ASSERT_EQ(face.cols(), regions::kFace.num_vertices());
  EXPECT_LT((full.leftCols(face.cols()) - face).cwiseAbs().maxCoeff(), 1e-5f);
  const Positions neck = model->evaluate(a, b, regions::kHeadAndNeck);
  EXPECT_LT((full.middleCols(regions::kHeadAndNeck.first_vertex, neck.cols()) - neck).cwiseAbs().maxCoeff(), 1e-5f);
}

TEST(FaceModel, AnIdentityShapeTakesExpressionsAsEvaluateDoes) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXf a = Eigen::VectorXf::Random(model->num_identity());
  const Eigen::VectorXf b = (Eigen::VectorXf::Random(model->num_expressions()).array() * 0.5f + 0.5f).matrix();
  const Eigen::VectorXf shape = model->identity_shape(a, regions::kFace);
  const Positions face = model->with_expression(shape, b, regions::kFace);
  EXPECT_LT((face - model->evaluate(a, b, regions::kFace)).cwiseAbs().maxCoeff(), 1e-5f);
  // No expression weights: the identity shape itself.
  const Positions neutral = model->with_expression(shape, Eigen::VectorXf(), regions::kFace);
  EXPECT_EQ((Eigen::Map<const Eigen::VectorXf>(neutral.data(), neutral.size()) - shape).cwiseAbs().maxCoeff(), 0.0f);
  // A shape of another region is refused.
  EXPECT_THROW(model->with_expression(shape, b, regions::kHeadAndNeck), Error);
}

TEST(FaceModel, FaceRegionMeshIsLocalAndUsesAllRegionVertices) {
  FACECAP_REQUIRE_MODEL(model);
  const TriangleMesh face = model->region_mesh(regions::kFace);
  EXPECT_EQ(face.num_vertices, 9409);
  std::vector<bool> used(face.num_vertices, false);
  for (const Triangle& t : face.triangles) {
    for (int v : t) {
      ASSERT_GE(v, 0);
      ASSERT_LT(v, face.num_vertices);
      used[v] = true;
    }
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), true), face.num_vertices);
  // Outward normals: the nose tip's normal points out of the face (+z).
  const Positions n =
      vertex_normals(model->evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace), face.triangles);
  EXPECT_GT(n(2, model->landmarks.vertices[30]), 0.9f);
}

}  // namespace facecap
