#include "facecap/fit/gaze.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "facecap/model/regions.hpp"
#include "facecap/synth/synth_renderer.hpp"
#include "test_support.hpp"

namespace facecap {
namespace {

HeadPose pose_of(double yaw, double pitch, double roll, const Vec3d& translation) {
  HeadPose p;
  p.rotation = axis_angle_from_rotation(rotation_from_yaw_pitch_roll_deg(yaw, pitch, roll));
  p.translation = translation;
  return p;
}

TEST(Eyeballs, AreTwoMirroredSpheresLookingAheadWithTheRightEyeOnTheImagesLeft) {
  FACECAP_REQUIRE_MODEL(model);
  const EyeballGeometry eyes = eyeball_geometry(*model, Eigen::VectorXd());
  for (int eye = 0; eye < 2; ++eye) {
    EXPECT_NEAR(eyes.radius[eye], 1.2, 0.1);  // a human eyeball is about 24 mm across
    EXPECT_GT(eyes.rest_axis[eye].z(), 0.99);
    EXPECT_GT(eyes.iris_depth(eye), 0.8 * eyes.radius[eye]);  // the iris ring lies 1-2 mm inside the sphere
    EXPECT_LT(eyes.iris_depth(eye), eyes.radius[eye]);
  }
  EXPECT_LT(eyes.centre[0].x(), -2.5);  // model x points to the subject's left
  EXPECT_NEAR(eyes.centre[0].x(), -eyes.centre[1].x(), 1e-4);
  EXPECT_NEAR(eyes.centre[0].y(), eyes.centre[1].y(), 1e-4);
  // Eye 0 is the one iBUG 36-41 mark, on the image's left for a frontal face.
  const PinholeCamera camera{1000, 320, 240};
  const HeadPose frontal = pose_of(0, 0, 0, Vec3d(0, 0, 60));
  Vec3d corners = Vec3d::Zero();
  for (int i = 36; i < 42; ++i)
    corners += model->neutral.segment<3>(3 * model->landmarks.vertices[i]).cast<double>() / 6;
  EXPECT_LT((corners - eyes.centre[0]).head<2>().norm(), 1.0);
  EXPECT_LT(project_iris_centre(eyes, 0, eyes.rest_axis[0], frontal, camera).x(), 320.0);
  EXPECT_GT(project_iris_centre(eyes, 1, eyes.rest_axis[1], frontal, camera).x(), 320.0);
}

TEST(Eyeballs, TurnToTheGazeTheAnglesName) {
  FACECAP_REQUIRE_MODEL(model);
  for (const auto& [yaw, pitch] : {std::pair{0.0, 0.0}, {20.0, -10.0}, {-35.0, 15.0}}) {
    const Mat3d r = gaze_rotation(yaw, pitch);
    EXPECT_LT((r.transpose() * r - Mat3d::Identity()).norm(), 1e-12);
    const Vec3d d = r * Vec3d::UnitZ();
    EXPECT_NEAR(gaze_angles_deg(d).x(), yaw, 1e-9);
    EXPECT_NEAR(gaze_angles_deg(d).y(), pitch, 1e-9);
  }
  EXPECT_GT((gaze_rotation(20, 0) * Vec3d::UnitZ()).x(), 0.3);  // toward the subject's left
  EXPECT_GT((gaze_rotation(0, 20) * Vec3d::UnitZ()).y(), 0.3);  // up

  // The eyeballs turn about their centres; the pupils go where turned_axis says.
  const Eigen::VectorXd identity = Eigen::VectorXd::Constant(10, 0.7);
  const EyeballGeometry eyes = eyeball_geometry(*model, identity);
  Positions head = model->evaluate(identity.cast<float>(), Eigen::VectorXf());
  const Positions before = head;
  turn_eyeballs(eyes, 25.0, -12.0, head);
  for (int eye = 0; eye < 2; ++eye) {
    const Vec3d pupil = head.col(eyes.pupil_vertex[eye]).cast<double>();
    const Vec3d expected = eyes.centre[eye] + eyes.radius[eye] * turned_axis(eyes, eye, 25.0, -12.0);
    EXPECT_LT((pupil - expected).norm(), 1e-4);
  }
  // Nothing but the eyeballs moves.
  EXPECT_EQ(head.leftCols(regions::kEyeballLeft.first_vertex), before.leftCols(regions::kEyeballLeft.first_vertex));
  EXPECT_EQ(head.rightCols(head.cols() - regions::kEyeballRight.last_vertex - 1),
            before.rightCols(head.cols() - regions::kEyeballRight.last_vertex - 1));
}

TEST(Gaze, AnIrisWhereATurnedEyeShowsItGivesThatTurnBack) {
  FACECAP_REQUIRE_MODEL(model);
  const EyeballGeometry eyes = eyeball_geometry(*model, Eigen::VectorXd::Constant(20, -0.5));
  const PinholeCamera camera{1400, 640, 360};
  for (const HeadPose& pose : {pose_of(0, 0, 0, Vec3d(0, 0, 60)), pose_of(-25, 8, 4, Vec3d(5, -3, 80)),
                               pose_of(30, -10, -5, Vec3d(-8, 2, 45))}) {
    for (const auto& [yaw, pitch] : {std::pair{0.0, 0.0}, {18.0, 6.0}, {-22.0, -9.0}}) {
      IrisCentres iris;
      std::array<Vec3d, 2> truth;
      for (int eye = 0; eye < 2; ++eye) {
        truth[eye] = turned_axis(eyes, eye, yaw, pitch);
        iris[eye] = project_iris_centre(eyes, eye, truth[eye], pose, camera);
      }
      const GazeEstimate g = estimate_gaze(eyes, pose, camera, iris);
      ASSERT_TRUE(g.eyes[0] && g.eyes[1]);
      for (int eye = 0; eye < 2; ++eye) {
        EXPECT_FALSE(g.eyes[eye]->ray_missed);
        EXPECT_LT(angle_between_deg(g.eyes[eye]->direction, truth[eye]), 1e-6);
        EXPECT_LT((g.eyes[eye]->camera_direction - pose.model_to_camera_rotation() * truth[eye]).norm(), 1e-8);
        EXPECT_LT((camera.project(g.eyes[eye]->camera_iris) - *iris[eye]).norm(), 1e-6);
      }
      EXPECT_LT(angle_between_deg(g.direction(), truth[0] + truth[1]), 1e-6);
      // One eye alone gives its own direction.
      const GazeEstimate one = estimate_gaze(eyes, pose, camera, {std::nullopt, iris[1]});
      EXPECT_FALSE(one.eyes[0].has_value());
      EXPECT_LT(angle_between_deg(one.direction(), truth[1]), 1e-6);
    }
  }
}

// An iris beside the eyeball (a dark gap between the fingers of a hand over
// the eye), or where only an eye turned beyond what eyes do would show it,
// gives no gaze; of two eyes that disagree beyond what vergence explains,
// the farther turned is dropped; no iris gives none.
TEST(Gaze, AnIrisWhereNoEyeCouldLookGivesNoGaze) {
  FACECAP_REQUIRE_MODEL(model);
  const EyeballGeometry eyes = eyeball_geometry(*model, Eigen::VectorXd());
  const PinholeCamera camera{1000, 320, 240};
  const HeadPose pose = pose_of(0, 0, 0, Vec3d(0, 0, 60));
  auto iris_at = [&](int eye, double yaw, double pitch) {
    return project_iris_centre(eyes, eye, turned_axis(eyes, eye, yaw, pitch), pose, camera);
  };
  const Vec2d ahead = iris_at(0, 0, 0);
  EXPECT_FALSE(estimate_gaze(eyes, pose, camera, {Vec2d(ahead + Vec2d(-200, 0)), std::nullopt}).valid());
  EXPECT_TRUE(estimate_gaze(eyes, pose, camera, {iris_at(0, 0, -43), std::nullopt}).valid());
  EXPECT_FALSE(estimate_gaze(eyes, pose, camera, {iris_at(0, 0, -47), std::nullopt}).valid());
  EXPECT_FALSE(estimate_gaze(eyes, pose, camera, {iris_at(0, 33, 33), std::nullopt}).valid());  // 46 deg
  // Turned 20 and 12 degrees from rest, to the subject's right and left
  // (rest axes 2 degrees outward each): 36 degrees apart, the right eye's the
  // farther turn.
  const GazeEstimate apart = estimate_gaze(eyes, pose, camera, {iris_at(0, -20, 0), iris_at(1, 12, 0)});
  EXPECT_FALSE(apart.eyes[0].has_value());
  ASSERT_TRUE(apart.eyes[1].has_value());
  EXPECT_NEAR(gaze_angles_deg(apart.eyes[1]->direction).x(), gaze_angles_deg(turned_axis(eyes, 1, 12, 0)).x(), 1e-6);
  // 12 and 12: 28 degrees apart, both kept.
  const GazeEstimate near = estimate_gaze(eyes, pose, camera, {iris_at(0, -12, 0), iris_at(1, 12, 0)});
  EXPECT_TRUE(near.eyes[0] && near.eyes[1]);
  EXPECT_FALSE(estimate_gaze(eyes, pose, camera, {}).valid());
}

// A frame's iris search waits for the tracker's pose (for the first frames,
// until the identity solve): it keeps a copy of the eyes, not the frame,
// and finds there what the whole frame gives.
TEST(Gaze, AnIrisSearchKeepsTheEyesNotTheFrame) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 1;
  o.still = true;
  const SynthPerformance perf = make_performance(*model, o);
  const SynthRenderer renderer(*model, perf);
  const SynthFrame& frame = perf.frames[0];
  std::mt19937_64 noise(3);
  cv::Mat grey;
  cv::cvtColor(renderer.render(frame, noise), grey, cv::COLOR_BGR2GRAY);
  const Landmarks landmarks = renderer.landmarks(frame);
  const auto expected = expected_irises(renderer.eyeballs(), frame.pose, perf.camera);

  const IrisSearch search = iris_search(grey, landmarks);
  EXPECT_EQ(grey.u->refcount, 1);  // nothing but `grey` holds the frame
  const IrisPair found = search(expected);
  for (int eye = 0; eye < 2; ++eye) {
    const auto whole = locate_iris(grey, landmarks, eye, expected[eye]);
    ASSERT_TRUE(whole.has_value()) << eye;
    ASSERT_TRUE(found[eye].has_value()) << eye;
    EXPECT_EQ(found[eye]->centre, whole->centre);
    EXPECT_LT((whole->centre - renderer.iris_centre(frame, eye)).norm(), 2.0);
  }
}

// The iris's expected size is its 11.7 mm at the eye's depth, and a head
// turned from the camera narrows it: by the cosine of the angle between each
// eye's axis and its line of sight.
TEST(Gaze, ExpectedIrisesNarrowAsTheHeadTurns) {
  FACECAP_REQUIRE_MODEL(model);
  const EyeballGeometry eyes = eyeball_geometry(*model, Eigen::VectorXd());
  const PinholeCamera camera{1000, 320, 240};
  const HeadPose frontal = pose_of(0, 0, 0, Vec3d(0, 0, 60));
  const std::array<IrisExpectation, 2> ahead = expected_irises(eyes, frontal, camera);
  for (int eye = 0; eye < 2; ++eye) {
    EXPECT_GT(ahead[eye].aspect, 0.99);
    // The camera looks along the model's -z: the eyes sit 8-9 cm ahead of the origin.
    EXPECT_NEAR(ahead[eye].radius_px, 1000 * kIrisRadiusCm / (60 - eyes.centre[eye].z()), 1e-9);
  }
  // Far away, where the eyes' lines of sight are nearly parallel, a 40
  // degree turn narrows the iris by the cosine of 40 degrees, give or take
  // the eyes' 2 degrees outward and a degree of parallax.
  const HeadPose turned = pose_of(40, 0, 0, Vec3d(0, 0, 600));
  for (const IrisExpectation& e : expected_irises(eyes, turned, camera)) {
    EXPECT_NEAR(std::acos(e.aspect) * 180 / 3.14159265358979, 40.0, 3.0);
  }
  const HeadPose behind = pose_of(0, 0, 0, Vec3d(0, 0, -60));
  for (const IrisExpectation& e : expected_irises(eyes, behind, camera)) EXPECT_EQ(e.radius_px, 0.0);
}

}  // namespace
}  // namespace facecap
