#include "facecap/render/shading.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace facecap {

namespace {

// A UV sphere of radius r centred at c, outward-facing.
void sphere(const Vec3f& c, float r, Positions& p, std::vector<Triangle>& t) {
  const int rings = 60, segs = 120;
  p.resize(3, (rings + 1) * segs);
  for (int i = 0; i <= rings; ++i) {
    const float th = 3.14159265f * i / rings;
    for (int j = 0; j < segs; ++j) {
      const float ph = 2 * 3.14159265f * j / segs;
      p.col(i * segs + j) = c + r * Vec3f(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segs; ++j) {
      const int a = i * segs + j, b = i * segs + (j + 1) % segs, cc = (i + 1) * segs + j,
                d = (i + 1) * segs + (j + 1) % segs;
      t.push_back({a, cc, b});
      t.push_back({b, cc, d});
    }
  }
}

}  // namespace

TEST(Shading, LambertianShIrradianceOnASphere) {
  Positions p;
  std::vector<Triangle> t;
  sphere(Vec3f(0, 0, 10), 2.0f, p, t);
  Positions n = vertex_normals(p, t);
  // Make sure the winding gave outward normals (flip the mesh otherwise).
  if (n.col(0).dot(p.col(0) - Vec3f(0, 0, 10)) < 0) {
    for (auto& tri : t) std::swap(tri[1], tri[2]);
    n = vertex_normals(p, t);
  }
  const PinholeCamera cam{200.0, 100.0, 100.0};
  RasterBuffers b;
  b.resize(200, 200);
  rasterize(p, t, cam, b);
  ShCoeffs l = ShCoeffs::Zero();
  l[0] = 0.6;
  l[2] = 0.3;  // from above (viewer frame y up)
  l[3] = 0.4;  // from the camera
  const Positions albedo = Positions::Constant(3, p.cols(), 0.5f);
  cv::Mat canvas(200, 200, CV_32FC3, cv::Scalar::all(0));
  shade_lambertian(b, t, albedo, n, l, canvas);
  // Centre: normal toward the viewer, shade = 0.6 + 0.4.
  EXPECT_NEAR(canvas.at<cv::Vec3f>(100, 100)[0], 0.5f * 1.0f, 0.01f);
  // The pixel 30 px up: normal tilted up, so the top light adds (y up in the viewer frame).
  const cv::Vec3f up = canvas.at<cv::Vec3f>(70, 100), down = canvas.at<cv::Vec3f>(130, 100);
  EXPECT_GT(up[0], down[0] + 0.05f);
  // Background untouched.
  EXPECT_EQ(canvas.at<cv::Vec3f>(2, 2)[0], 0.0f);
}

TEST(Shading, ShBasisMatchesThePaper) {
  const auto b = sh_basis(0.2, -0.3, 0.9);
  EXPECT_DOUBLE_EQ(b[0], 1.0);
  EXPECT_DOUBLE_EQ(b[4], 0.2 * -0.3);
  EXPECT_DOUBLE_EQ(b[7], 0.2 * 0.2 - 0.09);
  EXPECT_DOUBLE_EQ(b[8], 3 * 0.81 - 1);
  ShCoeffs l;
  l << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  EXPECT_NEAR(sh_shade(l, 0.2, -0.3, 0.9), l.dot(b), 1e-12);
}

}  // namespace facecap
