// render_swapped_face (eq. 6.7): texture times SH shading times the light's
// tint and gain maps, the texture's alpha as the face's share (a surface
// facing the camera is not faded: silhouette_fade_test.cpp).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "facecap/swap/face_render.hpp"

namespace facecap {

namespace {

// A 10 cm square 50 cm in front of the camera, facing it, its UVs the
// whole texture; 100 px wide in a 200 px window centred on it.
struct Square {
  TriangleMesh mesh;
  Positions points = Positions(3, 4);
  PinholeCamera camera{500.0, 100.0, 100.0};
  Square() {
    points << -5, 5, 5, -5,  //
        -5, -5, 5, 5,        //
        50, 50, 50, 50;
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    mesh.triangle_uvs = mesh.triangles;
    mesh.uvs = {Vec2f(0, 1), Vec2f(1, 1), Vec2f(1, 0), Vec2f(0, 0)};
    mesh.num_vertices = 4;
  }
};

}  // namespace

TEST(FaceRender, ShadesTheTextureWithTheLightsTintAndGains) {
  const Square sq;
  const Positions normals = vertex_normals(sq.points, sq.mesh.triangles);
  ASSERT_LT(normals(2, 0), -0.99f);  // toward the camera
  const TextureLevels texture(cv::Mat(64, 64, CV_32FC4, cv::Scalar(0.5, 0.4, 0.3, 0.75)));
  ShCoeffs lighting = ShCoeffs::Zero();
  lighting[0] = 0.8;

  cv::Mat alpha;
  const FaceLight plain;
  cv::Mat colour = render_swapped_face(sq.mesh, texture, sq.points, normals, sq.camera, sq.camera, cv::Size(200, 200),
                                       lighting, plain, 0.3f, alpha);
  ASSERT_EQ(colour.type(), CV_32FC3);
  ASSERT_EQ(alpha.size(), cv::Size(200, 200));
  const cv::Vec3f centre = colour.at<cv::Vec3f>(100, 100);
  EXPECT_NEAR(centre[0], 255 * 0.8 * 0.5, 0.05);
  EXPECT_NEAR(centre[1], 255 * 0.8 * 0.4, 0.05);
  EXPECT_NEAR(centre[2], 255 * 0.8 * 0.3, 0.05);
  EXPECT_NEAR(alpha.at<float>(100, 100), 0.75f, 1e-4);  // the texture's alpha: facing the camera, no fade
  EXPECT_EQ(alpha.at<float>(10, 10), 0.0f);             // off the square
  EXPECT_EQ(colour.at<cv::Vec3f>(10, 10), cv::Vec3f(0, 0, 0));
  EXPECT_NEAR(alpha.at<float>(100, 51), 0.75f, 1e-4);

  FaceLight light;
  light.tint = Vec3f(1.0f, 0.5f, 2.0f);
  light.residual_gains = cv::Mat(32, 32, CV_32FC3, cv::Scalar(1.0, 1.0, 0.5));
  light.expression_gains = cv::Mat(32, 32, CV_32F, cv::Scalar(1.5));
  colour = render_swapped_face(sq.mesh, texture, sq.points, normals, sq.camera, sq.camera, cv::Size(200, 200), lighting,
                               light, 0.3f, alpha);
  const cv::Vec3f lit = colour.at<cv::Vec3f>(100, 100);
  EXPECT_NEAR(lit[0], 204 * 0.5 * 1.0 * 1.0 * 1.5, 0.05);
  EXPECT_NEAR(lit[1], 204 * 0.4 * 0.5 * 1.0 * 1.5, 0.05);
  EXPECT_NEAR(lit[2], 204 * 0.3 * 2.0 * 0.5 * 1.5, 0.05);

  // A window of the frame: the same face, shifted.
  cv::Mat window_alpha;
  const cv::Mat shifted =
      render_swapped_face(sq.mesh, texture, sq.points, normals, sq.camera, sq.camera.cropped(40, 30),
                          cv::Size(120, 140), lighting, light, 0.3f, window_alpha);
  EXPECT_EQ(shifted.at<cv::Vec3f>(70, 60), lit);
  EXPECT_EQ(window_alpha.at<float>(70, 60), alpha.at<float>(100, 100));
}

}  // namespace facecap
