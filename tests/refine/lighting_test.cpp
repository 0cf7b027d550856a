#include "facecap/refine/lighting.hpp"

#include <gtest/gtest.h>

#include <random>

#include "facecap/render/shading.hpp"

namespace facecap {

TEST(Lighting, RecoversShExactlyWhenNormalsSpanTheSphere) {
  std::mt19937 rng(2);
  std::normal_distribution<float> n(0, 1);
  const int count = 2000;
  Positions normals(3, count), albedo(3, count);
  VertexSamples s;
  s.colour.resize(3, count);
  s.visible.assign(count, true);
  ShCoeffs l;
  l << 0.8, 0.2, 0.3, 0.4, 0.05, -0.04, 0.03, 0.06, 0.08;
  for (int i = 0; i < count; ++i) {
    normals.col(i) = Vec3f(n(rng), n(rng), n(rng)).normalized();
    albedo.col(i) = Vec3f(0.7f, 0.5f, 0.4f) * (0.8f + 0.4f * (i % 7) / 6.0f);
    const Vec3f v = to_viewer_frame(Vec3f(normals.col(i)));
    const float shade = sh_shade(l, v.x(), v.y(), v.z());
    s.colour.col(i) = albedo.col(i) * shade;
  }
  LightingOptions o;
  o.band2_ridge = 0.0;
  const ShCoeffs est = estimate_lighting(s, normals, albedo, std::nullopt, o);
  EXPECT_LT((est - l).norm() / l.norm(), 1e-4);
}

TEST(Lighting, OnlyVisibleVerticesCount) {
  Positions normals(3, 2), albedo = Positions::Constant(3, 2, 0.5f);
  normals << 0, 0, 0, 0, -1, -1;
  VertexSamples s;
  s.colour.resize(3, 2);
  s.colour.col(0) = Vec3f::Constant(0.5f);
  s.colour.col(1) = Vec3f::Constant(100.0f);  // an outlier, not visible
  s.visible = {true, false};
  LightingOptions o;
  o.band2_ridge = 0.0;
  const ShCoeffs est = estimate_lighting(s, normals, albedo, std::nullopt, o);
  const Vec3f v = to_viewer_frame(Vec3f(0, 0, -1));
  EXPECT_NEAR(sh_shade(est, v.x(), v.y(), v.z()), 1.0, 1e-3);
}

}  // namespace facecap
