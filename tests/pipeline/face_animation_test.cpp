#include "facecap/pipeline/face_animation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/eyeballs.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_matte.hpp"
#include "io/glb_reader.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(FaceAnimation, PlayedBackItReproducesTheTrackedMeshAndTheCameraView) {
  FACECAP_REQUIRE_MODEL(model);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Eigen::VectorXd identity(model->num_identity());
  for (auto& x : identity) x = normal(rng);
  std::vector<FaceAnimationKey> keys;
  for (int k = 0; k < 3; ++k) {
    FaceAnimationKey key;
    key.time = 0.04 * k;
    key.pose.rotation = Vec3d(0.1 * normal(rng), 0.4 * normal(rng), 0.1 * normal(rng));
    key.pose.translation = Vec3d(2 * normal(rng), 2 * normal(rng), 55 + 5 * normal(rng));
    key.expression = Eigen::VectorXf::Zero(model->num_expressions());
    for (int j = 0; j < 6; ++j) key.expression[(k * 11 + j * 7) % model->num_expressions()] = unit(rng);
    keys.push_back(key);
  }
  const FaceAnimationCamera camera{900.0, 1280, 720};
  TempDir dir;
  write_glb(dir.path() / "a.glb", face_animation(*model, identity, keys, camera));
  const test::Glb g = test::Glb::read(dir.path() / "a.glb");

  const std::vector<std::vector<int>> sources = face_animation_source_vertices(*model);
  const auto& prims = g.doc["meshes"][0]["primitives"];
  ASSERT_EQ(prims.size(), 2u);  // the face, and the mouth and eyes behind its holes
  ASSERT_EQ(sources.size(), 2u);
  for (size_t part = 0; part < 2; ++part)
    ASSERT_EQ(size_t(g.doc["accessors"][int(prims[part]["attributes"]["POSITION"])]["count"]), sources[part].size());
  EXPECT_GE(sources[0].size(), size_t(regions::kFace.num_vertices()));  // split at UV seams, never merged
  int teeth = 0, eyeballs = 0;
  for (int v : sources[1]) {
    teeth += v >= regions::kTeeth.first_vertex && v <= regions::kTeeth.last_vertex;
    eyeballs += v >= regions::kEyeballLeft.first_vertex && v <= regions::kEyeballRight.last_vertex;
    EXPECT_TRUE(v < regions::kHeadAndNeck.first_vertex || v > regions::kHeadAndNeck.last_vertex) << v;
  }
  EXPECT_GT(teeth, 1000);
  EXPECT_GT(eyeballs, 1000);
  EXPECT_EQ(g.doc["meshes"][0]["extras"]["targetNames"][0], model->expression_names[0]);
  const double aspect = g.doc["cameras"][0]["perspective"]["aspectRatio"];
  EXPECT_NEAR(aspect, 1280.0 / 720.0, 1e-9);

  const Eigen::Vector3f flip(1, -1, -1);  // glTF's world is the OpenCV camera frame turned about x
  const PinholeCamera cam = PinholeCamera::centered(camera.focal_px, camera.width, camera.height);
  for (int k = 0; k < 3; ++k) {
    const Positions truth = to_camera(model->evaluate(identity.cast<float>(), keys[k].expression), keys[k].pose);
    for (size_t part = 0; part < 2; ++part) {
      double worst_cm = 0, worst_px = 0;
      const Eigen::Matrix3Xf played = g.played_part(int(part), k);
      for (size_t i = 0; i < sources[part].size(); i += 37) {
        const Eigen::Vector3f world = played.col(Eigen::Index(i));
        const Eigen::Vector3f cam_cm = flip.cwiseProduct(world) * 100.0f;
        const Vec3f expected = truth.col(sources[part][i]);
        worst_cm = std::max(worst_cm, double((cam_cm - expected).norm()));
        // Through the glTF camera, against the tracker's pinhole projection.
        const Vec2d glt = g.camera_pixel(world, camera.width, camera.height);
        const Vec2d pin = cam.project(Vec3d(expected.cast<double>()));
        worst_px = std::max(worst_px, (glt - pin).cwiseAbs().maxCoeff());
      }
      EXPECT_LT(worst_cm, 1e-3) << "key " << k << " part " << part;
      // glTF's camera has no principal point: ours sits at half the image
      // size, half a pixel from the centre of a grid with integer centres.
      EXPECT_LT(worst_px, 0.5 + 1e-3) << "key " << k << " part " << part;
    }
  }
}

// The gaze plays back as the four eye-turn targets: the pupils point where
// the eyeballs turned by the key's angles point, and a key with no gaze (a
// blink) holds the one before.
TEST(FaceAnimation, TheEyeTurnTargetsPlayTheGaze) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXd identity = Eigen::VectorXd::Constant(20, 0.5);
  const std::array<std::optional<Vec2d>, 4> gazes = {Vec2d(20, -12), Vec2d(-28, 8), std::nullopt, Vec2d(0, 0)};
  std::vector<FaceAnimationKey> keys;
  for (size_t k = 0; k < gazes.size(); ++k) {
    FaceAnimationKey key;
    key.time = 0.04 * double(k);
    key.pose.rotation = Vec3d(0.05, 0.3, -0.02);
    key.expression = Eigen::VectorXf::Zero(model->num_expressions());
    key.gaze_deg = gazes[k];
    keys.push_back(key);
  }
  TempDir dir;
  write_glb(dir.path() / "a.glb", face_animation(*model, identity, keys, {900.0, 1280, 720}));
  const test::Glb g = test::Glb::read(dir.path() / "a.glb");
  const auto& names = g.doc["meshes"][0]["extras"]["targetNames"];
  ASSERT_EQ(names.size(), size_t(model->num_expressions()) + 4);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(names[model->num_expressions() + t], kEyeTurnTargetNames[t]);

  const std::vector<int> source = face_animation_source_vertices(*model)[1];
  const EyeballGeometry eyes = eyeball_geometry(*model, identity);
  const Positions rest = model->evaluate(identity.cast<float>(), Eigen::VectorXf());
  for (int k = 0; k < 4; ++k) {
    const Vec2d gaze = gazes[k] ? *gazes[k] : *gazes[1];
    Positions turned = rest;
    turn_eyeballs(eyes, gaze.x(), gaze.y(), turned);
    const Positions truth = to_camera(turned, keys[k].pose);
    const Eigen::Matrix3Xf played = g.played_part(1, k);
    for (int eye = 0; eye < 2; ++eye) {
      const Region& r = eyeball_region(eye);
      Eigen::Vector3f played_centre = Eigen::Vector3f::Zero(), played_pupil = Eigen::Vector3f::Zero();
      Vec3f true_centre = Vec3f::Zero();
      int n = 0;
      for (size_t i = 0; i < source.size(); ++i) {
        if (source[i] < r.first_vertex || source[i] > r.last_vertex) continue;
        played_centre += played.col(Eigen::Index(i));
        true_centre += truth.col(source[i]);
        ++n;
        if (source[i] == eyes.pupil_vertex[eye]) played_pupil = played.col(Eigen::Index(i));
      }
      ASSERT_EQ(n, r.num_vertices());
      const Eigen::Vector3f flip(1, -1, -1);  // glTF's world to the camera frame (metres to cm below)
      const Vec3d played_axis = (flip.cwiseProduct(played_pupil - played_centre / float(n))).cast<double>();
      const Vec3d true_axis = (truth.col(eyes.pupil_vertex[eye]) - true_centre / float(n)).cast<double>();
      // Offsets blend along chords, and the yaw and pitch targets' offsets add
      // where the turns would compose: 1.1-1.2 degrees off here, 0 at rest.
      EXPECT_LT(angle_between_deg(played_axis, true_axis), k == 3 ? 1e-3 : 1.5) << "key " << k << " eye " << eye;
    }
  }
}

// The eyeballs are coloured white with a dark iris and pupil round each
// eye's axis at rest (so the turned eyes show where they look): the pupil
// vertex black, the dark vertices centred on the axis within the iris's
// radius, everything farther round white.
TEST(FaceAnimation, EachEyeHasAnIrisRoundItsAxis) {
  FACECAP_REQUIRE_MODEL(model);
  const Eigen::VectorXd identity = Eigen::VectorXd::Constant(20, 0.5);
  FaceAnimationKey key;
  key.expression = Eigen::VectorXf::Zero(model->num_expressions());
  const GltfAnimatedMesh m = face_animation(*model, identity, {key}, {900.0, 1280, 720});
  ASSERT_EQ(m.primitives.size(), 2u);
  const Positions& colours = m.primitives[1].colours;
  const std::vector<int> source = face_animation_source_vertices(*model)[1];
  ASSERT_EQ(colours.cols(), Eigen::Index(source.size()));
  const EyeballGeometry eyes = eyeball_geometry(*model, identity);
  const Positions rest = model->evaluate(identity.cast<float>(), Eigen::VectorXf());
  for (int eye = 0; eye < 2; ++eye) {
    const Region& r = eyeball_region(eye);
    const double iris_deg = std::asin(kIrisRadiusCm / eyes.radius[eye]) * 180 / M_PI;
    Vec3d dark_sum = Vec3d::Zero();
    int dark = 0;
    for (size_t i = 0; i < source.size(); ++i) {
      if (source[i] < r.first_vertex || source[i] > r.last_vertex) continue;
      const Vec3d direction = (rest.col(source[i]).cast<double>() - eyes.centre[eye]).normalized();
      const double off_axis_deg = angle_between_deg(direction, eyes.rest_axis[eye]);
      const float brightness = colours.col(Eigen::Index(i)).mean();
      if (source[i] == eyes.pupil_vertex[eye]) {
        EXPECT_LT(brightness, 0.05f) << "eye " << eye;
      }
      if (brightness < 0.5f) {
        ++dark;
        dark_sum += direction;
        EXPECT_LT(off_axis_deg, iris_deg + 0.5) << "eye " << eye << " vertex " << source[i];
      } else if (off_axis_deg < iris_deg - 5) {
        ADD_FAILURE() << "eye " << eye << " vertex " << source[i] << " inside the iris is white";
      }
    }
    std::printf("eye %d: %d dark vertices, iris %.1f deg round the axis\n", eye, dark, iris_deg);
    EXPECT_GT(dark, 20) << "eye " << eye;
    EXPECT_LT(angle_between_deg(dark_sum, eyes.rest_axis[eye]), 2.0) << "eye " << eye;
  }
}

// The face matte travels in the file (as an image no material uses, which
// renderers ignore), so that a transform's or a swap's glTF, which has no
// track folder beside it, can be held out over the footage too.
TEST(FaceAnimation, TheFileCarriesTheFaceMatte) {
  FACECAP_REQUIRE_MODEL(model);
  FaceAnimationKey key;
  key.expression = Eigen::VectorXf::Zero(model->num_expressions());
  GltfAnimatedMesh m = face_animation(*model, Eigen::VectorXd::Zero(10), {key}, {900.0, 1280, 720});
  m.primitives[0].base_colour_png = encode_png(cv::Mat(8, 8, CV_8UC3, cv::Scalar(90, 120, 200)));  // an albedo
  TempDir dir;
  write_glb(dir.path() / "a.glb", m);
  const test::Glb g = test::Glb::read(dir.path() / "a.glb");
  ASSERT_EQ(g.doc["images"].size(), 2u);
  ASSERT_EQ(g.doc["textures"].size(), 1u);
  EXPECT_EQ(g.doc["textures"][0]["source"], 0);  // the albedo; nothing samples the matte
  EXPECT_EQ(g.doc["images"][1]["name"], kFaceMatteImageName);
  EXPECT_EQ(g.doc["images"][1]["mimeType"], "image/png");
  const std::string bytes = g.image_bytes(1);
  const cv::Mat matte = decode_image({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()});
  ASSERT_EQ(matte.size(), cv::Size(1024, 1024));
  cv::Mat grey;  // decoded as BGR, its channels equal
  cv::extractChannel(matte, grey, 0);
  EXPECT_EQ(cv::countNonZero(grey != face_matte_image(*model)), 0);
  EXPECT_NE(std::string(g.doc["asset"]["extras"]["face_matte"]).find("face_matte"), std::string::npos);
}

TEST(FaceAnimation, TooManyWeightsIsAnError) {
  FACECAP_REQUIRE_MODEL(model);
  FaceAnimationKey key;
  key.expression = Eigen::VectorXf::Zero(model->num_expressions() + 1);
  EXPECT_THROW(face_animation(*model, Eigen::VectorXd::Zero(model->num_identity()), {key}, {}), Error);
}

}  // namespace facecap
