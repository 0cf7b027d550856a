#include "facecap/fit/identity_size.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "facecap/core/rigid_alignment.hpp"
#include "facecap/model/regions.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

constexpr int kModes = 50;
constexpr double kAllAcross = kModes - 1;  // every direction across the size ray determined

Positions neutral_face(const FaceModel& model, const Eigen::VectorXd& identity) {
  return model.evaluate(identity.cast<float>(), Eigen::VectorXf(), regions::kFace);
}

}  // namespace

TEST(IdentitySize, TheCorrectedFaceIsTheSameShapeLarger) {
  FACECAP_REQUIRE_MODEL(model);
  const IdentitySizeCorrection size(*model, kModes);
  ASSERT_EQ(size.mean_coefficients().size(), kModes);
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  Eigen::VectorXd a(kModes);
  for (int k = 0; k < kModes; ++k) a[k] = 0.7 * n01(rng);  // a MAP fit is shrunk toward the mean face
  const double c = size.factor(a, kAllAcross);
  EXPECT_GT(c, 1.01);
  EXPECT_LT(c, 1.08);
  const Positions before = neutral_face(*model, a), after = neutral_face(*model, size.apply(a, kAllAcross));
  // The same shape up to a similarity, grown by about c. The part of the
  // neutral face that the identity modes cannot express (6 % of it, centred)
  // does not grow: 0.15 mm of shape change on ICT.
  const RigidTransform t = align_rigid(before, after, true);
  EXPECT_NEAR(t.scale, c, 0.25 * (c - 1));
  EXPECT_LT(aligned_mean_distance(before, after, true), 0.02);  // cm
  EXPECT_GT(aligned_mean_distance(before, after), 0.1);         // a rigid alignment sees the growth
  // The mean face is the one identity the prior likes best: it grows by the
  // closed form with d.m = |m|.
  const double m2 = size.mean_coefficients().squaredNorm();
  EXPECT_NEAR(size.factor(Eigen::VectorXd::Zero(kModes), kAllAcross), 0.5 * (1 + std::sqrt(1 + 4 * kAllAcross / m2)),
              1e-9);
  // Landmarks that determine fewer directions grow it less.
  EXPECT_LT(size.factor(a, 20), c);
  EXPECT_GT(size.factor(a, 20), 1.0);
}

// Moved over the vertices the landmarks are fitted to, those keep their shape
// exactly enough for the fit to the landmarks to stay, and the face region
// still grows by the factor.
TEST(IdentitySize, TheLandmarkVerticesGrowAsOne) {
  FACECAP_REQUIRE_MODEL(model);
  const std::vector<int>& landmarks = model->landmarks.vertices;
  const IdentitySizeCorrection size(*model, kModes, landmarks);
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  Eigen::VectorXd a(kModes);
  for (int k = 0; k < kModes; ++k) a[k] = 0.7 * n01(rng);
  const double c = size.factor(a, kAllAcross);
  const Eigen::VectorXd grown = size.apply(a, kAllAcross);
  const Positions before = model->evaluate(a.cast<float>(), Eigen::VectorXf());
  const Positions after = model->evaluate(grown.cast<float>(), Eigen::VectorXf());
  Positions lm_before(3, landmarks.size()), lm_after(3, landmarks.size());
  for (size_t i = 0; i < landmarks.size(); ++i) {
    lm_before.col(i) = before.col(landmarks[i]);
    lm_after.col(i) = after.col(landmarks[i]);
  }
  // 0.06 mm of shape change at the landmarks; the move over the face region
  // leaves 0.14 mm there.
  EXPECT_LT(aligned_mean_distance(lm_before, lm_after, true), 0.008);  // cm
  EXPECT_NEAR(align_rigid(lm_before, lm_after, true).scale, c, 0.1 * (c - 1));
  EXPECT_NEAR(align_rigid(neutral_face(*model, a), neutral_face(*model, grown), true).scale, c, 0.25 * (c - 1));
}

// The claim the correction rests on: for identities drawn from the model's
// prior, the joint mode along each one's size ray is too small on average,
// and the corrected length is right on average.
TEST(IdentitySize, UnderThePriorTheCorrectedSizeIsUnbiased) {
  FACECAP_REQUIRE_MODEL(model);
  const IdentitySizeCorrection size(*model, kModes);
  const Eigen::VectorXd& m = size.mean_coefficients();
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  double log_ratio_mode = 0, log_ratio_corrected = 0;
  const int draws = 400;
  for (int i = 0; i < draws; ++i) {
    Eigen::VectorXd truth(kModes);
    for (int k = 0; k < kModes; ++k) truth[k] = n01(rng);
    const Eigen::VectorXd ray = (truth + m).normalized();
    // What landmarks leave of the truth: its ray; the prior's peak on it.
    const Eigen::VectorXd mode = ray.dot(m) * ray - m;
    const Eigen::VectorXd corrected = size.apply(mode, kAllAcross);
    log_ratio_mode += std::log((mode + m).norm() / (truth + m).norm()) / draws;
    log_ratio_corrected += std::log((corrected + m).norm() / (truth + m).norm()) / draws;
  }
  EXPECT_LT(log_ratio_mode, -0.02);  // the joint mode: over 2 % too small
  EXPECT_NEAR(log_ratio_corrected, 0.0, 0.005);
}

TEST(IdentitySize, IdentitiesItCannotPlaceAreLeftAlone) {
  FACECAP_REQUIRE_MODEL(model);
  const IdentitySizeCorrection size(*model, kModes);
  EXPECT_EQ(size.factor(Eigen::VectorXd::Zero(kModes + 1), kAllAcross), 1.0);  // another mode count
  EXPECT_EQ(size.factor(-size.mean_coefficients(), kAllAcross), 1.0);          // zero length: no ray
  EXPECT_EQ(size.factor(Eigen::VectorXd::Zero(kModes), 0.0), 1.0);             // nothing determined
  const Eigen::VectorXd nan = Eigen::VectorXd::Constant(kModes, std::nan(""));
  EXPECT_EQ(size.factor(nan, kAllAcross), 1.0);
  EXPECT_EQ(size.factor(Eigen::VectorXd::Zero(kModes), std::nan("")), 1.0);
  EXPECT_TRUE(size.apply(nan, kAllAcross).hasNaN());  // passed through, not made up
}

}  // namespace facecap
