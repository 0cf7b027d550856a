// The target light's colour, from the face against its own albedo.
#include "facecap/swap/light_colour.hpp"

#include <gtest/gtest.h>

#include "facecap/render/shading.hpp"

namespace facecap {

namespace {

// A 20 x 20 grid of vertices, 1 cm apart, facing the camera 50 cm away.
struct FacingGrid {
  Positions points = Positions(3, 400);
  Positions normals = Positions(3, 400);
  Positions albedo = Positions(3, 400);
  std::vector<float> seen = std::vector<float>(400, 1.0f);
  PinholeCamera camera = PinholeCamera::centered(800.0, 640, 480);
  ShCoeffs lighting = ShCoeffs::Zero();

  FacingGrid() {
    lighting[0] = 0.9;
    lighting[2] = -0.2;
    for (int i = 0; i < 400; ++i) {
      points.col(i) = Vec3f(float(i % 20) - 9.5f, float(i / 20) - 9.5f, 50.0f);
      normals.col(i) = Vec3f(0, 0, -1);
      // Skin-like BGR albedo that varies across the grid.
      albedo.col(i) = Vec3f(0.30f + 0.01f * float(i % 7), 0.40f, 0.55f + 0.01f * float(i % 5));
    }
  }

  float shade() const {
    const Vec3f n = to_viewer_frame(Vec3f(0, 0, -1));
    return sh_shade(lighting, n.x(), n.y(), n.z());
  }

  // The frame the grid's albedo makes under the lighting, each channel
  // scaled by `light`, painted around each vertex's projection.
  cv::Mat frame(const Vec3f& light) const {
    cv::Mat image(480, 640, CV_8UC3, cv::Scalar(40, 40, 40));
    for (int i = 0; i < 400; ++i) {
      const Vec2f q = camera.project(Vec3f(points.col(i)));
      cv::Vec3b c;
      for (int k = 0; k < 3; ++k) c[k] = cv::saturate_cast<uchar>(255.0f * albedo(k, i) * shade() * light[k]);
      image(cv::Rect(int(q.x()) - 3, int(q.y()) - 3, 8, 8)).setTo(cv::Scalar(c[0], c[1], c[2]));
    }
    return image;
  }
};

// The tint of `frame` from the grid's vertices it shows.
Vec3f tint_of(const FacingGrid& g, const cv::Mat& frame, const LightColourOptions& options = {}) {
  return light_colour(lit_vertices(frame, g.points, g.normals, g.seen, g.camera, g.lighting), g.albedo, options);
}

}  // namespace

TEST(LightColour, AWarmerLightTintsByItsChromaticPart) {
  const FacingGrid g;
  const Vec3f light(0.9f, 1.0f, 1.15f);  // BGR: warmer than the albedo frames' light
  const Vec3f tint = tint_of(g, g.frame(light));
  const Vec3f expected = light / light.mean();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(tint[c], expected[c], 0.01f) << "channel " << c;
}

TEST(LightColour, ABrighterOrUnchangedLightGivesNoTint) {
  const FacingGrid g;
  for (const float brightness : {1.0f, 1.2f}) {
    const Vec3f tint = tint_of(g, g.frame(Vec3f::Constant(brightness)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(tint[c], 1.0f, 0.01f) << "brightness " << brightness << " channel " << c;
  }
}

TEST(LightColour, UnseenOrTurnedAwayVerticesGiveNoTint) {
  FacingGrid g;
  const cv::Mat warm = g.frame(Vec3f(0.8f, 1.0f, 1.2f));
  FacingGrid unseen = g;
  std::fill(unseen.seen.begin(), unseen.seen.end(), 0.0f);
  EXPECT_TRUE(tint_of(unseen, warm).isApprox(Vec3f::Ones()));
  FacingGrid edge_on = g;
  edge_on.normals.row(2).setZero();
  edge_on.normals.row(0).setOnes();
  EXPECT_TRUE(tint_of(edge_on, warm).isApprox(Vec3f::Ones()));
}

TEST(LightColour, TheTintIsClamped) {
  const FacingGrid g;
  const Vec3f tint = tint_of(g, g.frame(Vec3f(0.2f, 1.0f, 1.0f)), LightColourOptions{.max_gain = 1.25f});
  EXPECT_NEAR(tint[0], 0.8f, 1e-5f);
}

}  // namespace facecap
