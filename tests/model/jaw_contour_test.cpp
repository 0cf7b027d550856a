#include "facecap/model/jaw_contour.hpp"

#include <gtest/gtest.h>

#include "facecap/core/camera.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

std::array<int, 17> silhouette_at_yaw(const FaceModel& model, const JawContour& contour, double yaw) {
  const Positions face = model.evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace);
  HeadPose pose;
  pose.rotation = axis_angle_from_rotation(rotation_from_yaw_pitch_roll_deg(yaw, 0, 0));
  pose.translation = Vec3d(0, 0, 60);
  return silhouette_vertices(contour, face, pose.model_to_camera_rotation(), pose.translation);
}

}  // namespace

TEST(JawContour, FrontalSilhouetteIsTheJawline) {
  FACECAP_REQUIRE_MODEL(model);
  const JawContour contour = build_jaw_contour(*model);
  for (int k = 0; k < 17; ++k) {
    EXPECT_FALSE(contour.lines[k].empty());
    if (k != 8) {
      EXPECT_GE(contour.lines[k].size(), 3u) << "line " << k;
    }
  }
  const Positions face = model->evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace);
  const auto frontal = silhouette_at_yaw(*model, contour, 0.0);
  // Facing the camera, each jaw landmark projects onto its FACTS.md jawline
  // candidate or at most 2 mm (at the face's depth) outside it: under
  // perspective the outline sits slightly in front of the orthographic one.
  // At f = 1000 px and 56 cm, 2 mm is 3.6 px.
  auto image_x = [&](int v) { return 1000.0 * face(0, v) / (60.0 - face(2, v)); };
  for (int k = 0; k < 17; ++k) {
    const int candidate = k < 8    ? model->landmarks.jaw_right[k]
                          : k == 8 ? model->landmarks.vertices[8]
                                   : model->landmarks.jaw_left[k - 9];
    EXPECT_LT(std::abs(image_x(frontal[k]) - image_x(candidate)), 1000.0 * 0.2 / 56.0) << "landmark " << k;
  }
}

TEST(JawContour, SideTurningAwayMovesInward) {
  FACECAP_REQUIRE_MODEL(model);
  const JawContour contour = build_jaw_contour(*model);
  const Eigen::Map<const Positions> v(model->neutral.data(), 3, model->num_vertices);
  // Positive yaw (about the camera's down axis) brings the subject's left side
  // toward the camera and turns the right side (landmarks 0-7) away.
  const auto turned = silhouette_at_yaw(*model, contour, 30.0);
  for (int k = 0; k <= 5; ++k) {
    EXPECT_LT(std::abs(v(0, turned[k])), std::abs(v(0, model->landmarks.jaw_right[k])) - 1.0f) << "landmark " << k;
  }
  // The side facing the camera keeps its jawline.
  for (int k = 9; k <= 16; ++k) EXPECT_EQ(turned[k], model->landmarks.jaw_left[k - 9]) << "landmark " << k;
}

// The camera rolled about its axis (a head on a pillow, a camera on its
// side) turns the face's image and nothing else: by quarter turns and
// half-way between them, the silhouette is made of the same vertices as
// upright. Measured outermost along the image x axis, as before
// image_lateral(), a face rolled that far had its jaw points chosen across
// the outline (the fit of a clip turned 90 or 180 degrees then lay 1.1 px
// from the upright clip's, against 0.3-0.5 px).
TEST(JawContour, RollingTheCameraKeepsTheSilhouette) {
  FACECAP_REQUIRE_MODEL(model);
  const JawContour contour = build_jaw_contour(*model);
  const Positions face = model->evaluate(Eigen::VectorXf(), Eigen::VectorXf(), regions::kFace);
  const Vec3d translation(0, 0, 60);
  for (const double yaw : {-40.0, -15.0, 0.0, 25.0}) {
    for (const double pitch : {-15.0, 10.0}) {
      HeadPose pose;
      pose.rotation = axis_angle_from_rotation(rotation_from_yaw_pitch_roll_deg(yaw, pitch, 0));
      const Mat3d upright = pose.model_to_camera_rotation();
      const auto expected = silhouette_vertices(contour, face, upright, translation);
      for (const double roll : {45.0, 90.0, 135.0, 180.0, -90.0}) {
        const Mat3d camera_roll = Eigen::AngleAxisd(roll * M_PI / 180.0, Vec3d::UnitZ()).toRotationMatrix();
        // Rolling the camera turns the head's position with it.
        const auto rolled = silhouette_vertices(contour, face, camera_roll * upright, camera_roll * translation);
        int same = 0;
        for (int k = 0; k < 17; ++k) same += rolled[k] == expected[k];
        EXPECT_EQ(same, 17) << "yaw " << yaw << " pitch " << pitch << " roll " << roll;
      }
    }
  }
}

}  // namespace facecap
