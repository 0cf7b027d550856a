#include "facecap/fit/shape_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "facecap/fit/identity_size.hpp"
#include "facecap/model/regions.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

constexpr int kModes = 50;

// RMS (mm) of the centred face region's change from `identity` to `other`.
double centred_change_rms_mm(const FaceModel& model, const Eigen::VectorXd& identity, const Eigen::VectorXd& other) {
  const Positions a = model.evaluate(identity.cast<float>(), Eigen::VectorXf(), regions::kFace);
  const Positions b = model.evaluate(other.cast<float>(), Eigen::VectorXf(), regions::kFace);
  Eigen::Matrix3Xd d = (b - a).cast<double>();
  d.colwise() -= d.rowwise().mean();
  return 10.0 * std::sqrt(d.squaredNorm() / double(d.cols()));
}

}  // namespace

// The prediction against sampling: identities drawn from a covariance S move
// the face region by sqrt(trace(G S)) RMS.
TEST(ShapeUncertainty, PredictsTheSpreadOfSampledFaces) {
  FACECAP_REQUIRE_MODEL(model);
  const ShapeUncertainty uncertainty(*model, kModes);
  // A covariance like a fit's: the first modes pinned by landmarks, the rest
  // left to the prior, with some correlation.
  Eigen::MatrixXd root = Eigen::MatrixXd::Zero(kModes, kModes);
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  for (int k = 0; k < kModes; ++k) {
    root(k, k) = k < 20 ? 0.2 : 1.0;
    if (k > 0) root(k, k - 1) = 0.3 * n01(rng);
  }
  const Eigen::MatrixXd covariance = root * root.transpose();
  const double predicted = uncertainty.rms_mm(covariance);
  EXPECT_GT(predicted, 0.5);
  EXPECT_LT(predicted, 10.0);

  const Eigen::VectorXd centre = Eigen::VectorXd::Zero(kModes);
  double mean_square = 0;
  constexpr int kDraws = 400;
  for (int i = 0; i < kDraws; ++i) {
    Eigen::VectorXd z(kModes);
    for (int k = 0; k < kModes; ++k) z[k] = n01(rng);
    const double rms = centred_change_rms_mm(*model, centre, root * z);
    mean_square += rms * rms / kDraws;
  }
  // 400 draws of a sum over ~50 chi-square terms: a few per cent of spread.
  EXPECT_NEAR(std::sqrt(mean_square), predicted, 0.05 * predicted);
}

// Uncertainty along the size ray is size, not shape: held out by
// fixed_size_rms_mm, and only that.
TEST(ShapeUncertainty, TheSizeRayIsHeldOut) {
  FACECAP_REQUIRE_MODEL(model);
  const ShapeUncertainty uncertainty(*model, kModes);
  const IdentitySizeCorrection size(*model, kModes);
  Eigen::VectorXd identity(kModes);
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  for (int k = 0; k < kModes; ++k) identity[k] = n01(rng);
  const Eigen::VectorXd ray = identity + size.mean_coefficients();
  const Eigen::VectorXd u = ray.normalized();

  // All of it along the ray: a face that only grows and shrinks.
  const Eigen::MatrixXd along = 0.02 * 0.02 * ray * ray.transpose();  // 2 % of size, one sigma
  EXPECT_GT(uncertainty.rms_mm(along), 0.3);
  EXPECT_LT(uncertainty.fixed_size_rms_mm(along, ray), 1e-6);
  // A 2 % larger face moves its vertices by what rms_mm says.
  EXPECT_NEAR(centred_change_rms_mm(*model, identity, identity + 0.02 * ray), uncertainty.rms_mm(along), 1e-3);

  // None of it along the ray: untouched.
  const Eigen::MatrixXd across = Eigen::MatrixXd::Identity(kModes, kModes) - u * u.transpose();
  EXPECT_NEAR(uncertainty.fixed_size_rms_mm(across, ray), uncertainty.rms_mm(across), 1e-9);
  // The prior alone (S = I) holds both parts.
  const Eigen::MatrixXd prior = Eigen::MatrixXd::Identity(kModes, kModes);
  EXPECT_LT(uncertainty.fixed_size_rms_mm(prior, ray), uncertainty.rms_mm(prior));
  EXPECT_GT(uncertainty.fixed_size_rms_mm(prior, ray), 0.5 * uncertainty.rms_mm(prior));
}

TEST(ShapeUncertainty, AMisSizedCovarianceIsZeroNotACrash) {
  FACECAP_REQUIRE_MODEL(model);
  const ShapeUncertainty uncertainty(*model, kModes);
  EXPECT_EQ(uncertainty.rms_mm(Eigen::MatrixXd()), 0.0);
  EXPECT_EQ(uncertainty.rms_mm(Eigen::MatrixXd::Identity(3, 3)), 0.0);
}

}  // namespace facecap
