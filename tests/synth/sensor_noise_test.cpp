#include "facecap/synth/sensor_noise.hpp"

#include <gtest/gtest.h>

namespace facecap {
namespace {

// The renders' noise as it was drawn before add_sensor_noise (and as the
// synthetic figures in the README were measured): a grey draw and three
// colour draws a pixel from std::normal_distribution<float>.
cv::Mat distribution_noise(cv::Size size, double sigma, std::mt19937_64& rng) {
  cv::Mat noise(size, CV_32FC3);
  std::normal_distribution<float> n(0.0f, float(sigma / 255.0));
  for (auto it = noise.begin<cv::Vec3f>(); it != noise.end<cv::Vec3f>(); ++it) {
    const float g = n(rng);
    const float c2 = n(rng), c1 = n(rng), c0 = n(rng);  // a constructor's arguments, as GCC evaluated them
    *it = cv::Vec3f(g, g, g) + cv::Vec3f(c0, c1, c2) * 0.3f;
  }
  return noise;
}

TEST(SensorNoise, DrawsWhatTheDistributionDrawsAndLeavesTheStreamWhereItWould) {
  for (const uint64_t seed : {3ull, 104732ull}) {
    std::mt19937_64 ours(seed), theirs(seed);
    cv::Mat image(97, 131, CV_32FC3, cv::Scalar::all(0.5));
    add_sensor_noise(image, 1.5, ours);
    const cv::Mat expected = distribution_noise(image.size(), 1.5, theirs) + cv::Scalar::all(0.5);
    // The same draws; a last bit may differ where the compiler fused the
    // distribution's arithmetic otherwise, as it does in this file (6e-8);
    // the renders it replaced encode to the same video, bit for bit.
    EXPECT_LT(cv::norm(image, expected, cv::NORM_INF), 1e-6) << seed;
    EXPECT_GT(cv::norm(cv::Mat(image - cv::Scalar::all(0.5)), cv::NORM_INF), 0.01);  // some 3 sigma
    EXPECT_EQ(ours(), theirs());  // the next frame's noise starts where it did
  }
}

}  // namespace
}  // namespace facecap
