// The brightness pattern the target's SH lighting leaves unexplained.
#include "facecap/swap/residual_shading.hpp"

#include <gtest/gtest.h>

#include "facecap/core/error.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/render/uv_raster.hpp"

namespace facecap {

namespace {

// A 21 x 21 grid of vertices, 1 cm apart, facing the camera 60 cm away,
// with UVs spanning [0, 1]^2 (200 mm per UV unit) and v up as y goes up.
struct FacingGrid {
  static constexpr int kSide = 21;
  static constexpr int kCount = kSide * kSide;
  TriangleMesh mesh;
  Positions points = Positions(3, kCount);
  Positions normals = Positions(3, kCount);
  Positions albedo = Positions(3, kCount);
  std::vector<float> seen = std::vector<float>(kCount, 1.0f);
  PinholeCamera camera = PinholeCamera::centered(900.0, 640, 640);
  ShCoeffs lighting = ShCoeffs::Zero();

  FacingGrid() {
    lighting[0] = 0.9;
    lighting[2] = -0.2;
    mesh.num_vertices = kCount;
    for (int i = 0; i < kCount; ++i) {
      const int col = i % kSide, row = i / kSide;
      // Camera y points down the image; row 0 is the top of the grid.
      points.col(i) = Vec3f(float(col) - 10.0f, float(row) - 10.0f, 60.0f);
      normals.col(i) = Vec3f(0, 0, -1);
      albedo.col(i) = Vec3f(0.30f + 0.01f * float(i % 7), 0.40f, 0.55f + 0.01f * float(i % 5));
      mesh.uvs.emplace_back(float(col) / (kSide - 1), 1.0f - float(row) / (kSide - 1));
    }
    for (int row = 0; row + 1 < kSide; ++row) {
      for (int col = 0; col + 1 < kSide; ++col) {
        const int a = row * kSide + col, b = a + 1, c = a + kSide, d = c + 1;
        mesh.triangles.push_back({a, b, d});
        mesh.triangles.push_back({a, d, c});
      }
    }
    mesh.triangle_uvs = mesh.triangles;
  }

  float shade() const {
    const Vec3f n = to_viewer_frame(Vec3f(0, 0, -1));
    return sh_shade(lighting, n.x(), n.y(), n.z());
  }

  // A light's gain on channel k: one for all, or one per BGR channel.
  static float channel(float gain, int) { return gain; }
  static float channel(const Vec3f& gain, int k) { return gain[k]; }

  // The frame the albedo makes under the lighting, each vertex's
  // neighbourhood scaled by light(row).
  template <typename Light>
  cv::Mat frame(Light light) const {
    cv::Mat image(640, 640, CV_8UC3, cv::Scalar(40, 40, 40));
    for (int i = 0; i < kCount; ++i) {
      const Vec2f q = camera.project(Vec3f(points.col(i)));
      cv::Vec3b c;
      for (int k = 0; k < 3; ++k)
        c[k] = cv::saturate_cast<uchar>(255.0f * albedo(k, i) * shade() * channel(light(i / kSide), k));
      image(cv::Rect(int(q.x()) - 4, int(q.y()) - 4, 9, 9)).setTo(cv::Scalar(c[0], c[1], c[2]));
    }
    return image;
  }

  // The gain field of that frame at a low-pass scale.
  template <typename Light>
  cv::Mat field(Light light, float low_pass_mm = ResidualShadingOptions().low_pass_mm) const {
    ResidualShadingOptions options;
    options.low_pass_mm = low_pass_mm;
    return ResidualShading(mesh, points, options)
        .gains(lit_vertices(frame(light), points, normals, seen, camera, lighting), albedo);
  }

  // The field at a grid row's middle vertex: one BGR channel, or their mean.
  static float at_row(const cv::Mat& field, int row, int channel = -1) {
    const Vec2f t = uv_to_texel(Vec2f(0.5f, 1.0f - float(row) / (kSide - 1)), field.cols);
    const cv::Vec3f g = sample_bilinear_channels<3>(field, t.x(), t.y());
    return channel < 0 ? (g[0] + g[1] + g[2]) / 3.0f : g[channel];
  }
};

}  // namespace

TEST(ResidualShading, MillimetresPerUvComeFromTheMesh) {
  const FacingGrid g;
  const ResidualShading r(g.mesh, g.points);
  EXPECT_NEAR(r.mm_per_uv(), 200.0, 1e-3);
  EXPECT_GE(r.grid_size(), 16);
}

TEST(ResidualShading, AFaceTheLightingExplainsKeepsGainOne) {
  const FacingGrid g;
  const cv::Mat field = g.field([](int) { return 1.0f; });
  double lo = 0, hi = 0;
  cv::minMaxLoc(field.reshape(1), &lo, &hi);
  EXPECT_GT(lo, 0.97);
  EXPECT_LT(hi, 1.03);
}

TEST(ResidualShading, OverallBrightnessIsLeftToTheLighting) {
  const FacingGrid g;
  const cv::Mat field = g.field([](int) { return 1.15f; });
  EXPECT_NEAR(FacingGrid::at_row(field, 5), 1.0f, 0.03f);
  EXPECT_NEAR(FacingGrid::at_row(field, 15), 1.0f, 0.03f);
}

TEST(ResidualShading, LightFallingOffDownTheFaceIsFollowed) {
  const FacingGrid g;
  // The lower half 20 % darker than the lighting says.
  const cv::Mat field = g.field([](int row) { return row > 10 ? 0.8f : 1.0f; }, 15.0f);
  const float top = FacingGrid::at_row(field, 2), bottom = FacingGrid::at_row(field, 18);
  EXPECT_NEAR(bottom / top, 0.8f, 0.03f);
  EXPECT_LT(bottom, 1.0f);
  EXPECT_GT(top, 1.0f);
}

TEST(ResidualShading, ColourChangingDownTheFaceIsFollowedPerChannel) {
  const FacingGrid g;
  // The lower half 15 % bluer than the lighting says (BGR): a coloured
  // bounce light from below, say. Red and green stay as they were.
  const cv::Mat field = g.field([](int row) { return row > 10 ? Vec3f(1.15f, 1, 1) : Vec3f(1, 1, 1); }, 15.0f);
  EXPECT_NEAR(FacingGrid::at_row(field, 18, 0) / FacingGrid::at_row(field, 2, 0), 1.15f, 0.03f);
  for (int c : {1, 2}) {
    EXPECT_NEAR(FacingGrid::at_row(field, 2, c), 1.0f, 0.02f) << "channel " << c;
    EXPECT_NEAR(FacingGrid::at_row(field, 18, c), 1.0f, 0.02f) << "channel " << c;
  }
}

TEST(ResidualShading, ThePatternIsLowPass) {
  const FacingGrid g;
  // Rows alternating 15 % darker and lighter every centimetre: detail, not light.
  const cv::Mat field = g.field([](int row) { return row % 2 ? 0.85f : 1.15f; }, 20.0f);
  for (int row = 4; row <= 16; ++row) EXPECT_NEAR(FacingGrid::at_row(field, row), 1.0f, 0.03f) << "row " << row;
}

TEST(ResidualShading, GainsAreClamped) {
  const FacingGrid g;
  const cv::Mat field = g.field([](int row) { return row > 10 ? 0.3f : 1.0f; }, 10.0f);
  double lo = 0, hi = 0;
  cv::minMaxLoc(field.reshape(1), &lo, &hi);
  const float max_gain = ResidualShadingOptions().max_gain;
  EXPECT_GE(lo, 1.0 / max_gain - 1e-6);
  EXPECT_LE(hi, max_gain + 1e-6);
  EXPECT_LT(lo, 1.0 / max_gain + 1e-3);  // the lower half is clamped
}

TEST(ResidualShading, NothingSeenGivesOnes) {
  FacingGrid g;
  g.seen.assign(g.seen.size(), 0.0f);
  const cv::Mat field = g.field([](int row) { return row > 10 ? 0.8f : 1.0f; });
  EXPECT_EQ(cv::countNonZero(field.reshape(1) != 1.0f), 0);
}

TEST(ResidualShading, AMeshWithoutUvExtentIsRefused) {
  FacingGrid g;
  for (Vec2f& uv : g.mesh.uvs) uv = Vec2f(0.5f, 0.5f);
  EXPECT_THROW(ResidualShading(g.mesh, g.points), Error);
}

TEST(ResidualShading, ANonPositiveWidthIsRefused) {
  const FacingGrid g;
  for (const float width : {0.0f, -5.0f}) {
    ResidualShadingOptions options;
    options.low_pass_mm = width;
    EXPECT_THROW(ResidualShading(g.mesh, g.points, options), Error) << width;
  }
}

}  // namespace facecap
