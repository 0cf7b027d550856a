#include "facecap/compose/face_reshading.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/model/regions.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

struct Scene {
  cv::Mat frame;
  PinholeCamera camera = PinholeCamera::centered(500, 400, 300);
  HeadPose pose;
  TriangleMesh face;
  ShCoeffs lighting = ShCoeffs::Zero();
};

Scene make_scene(const FaceModel& model) {
  Scene s;
  s.frame = cv::Mat(300, 400, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(s.frame, cv::RNG::UNIFORM, 40, 220);
  cv::GaussianBlur(s.frame, s.frame, cv::Size(0, 0), 2.0);
  s.face = model.region_mesh(regions::kFace);
  s.lighting[0] = 0.8;
  s.lighting[2] = 0.3;  // light from the front and a little above
  s.lighting[3] = 0.2;
  return s;
}

Positions posed(const FaceModel& model, const Scene& s, const Eigen::VectorXf& weights) {
  return to_camera(model.evaluate(Eigen::VectorXf::Zero(model.num_identity()), weights, regions::kFace), s.pose);
}

int expression(const FaceModel& model, const std::string& name) { return model.expression_index(name); }

}  // namespace

TEST(FaceReshading, TheSameGeometryReproducesTheFrame) {
  FACECAP_REQUIRE_MODEL(model);
  const Scene s = make_scene(*model);
  const Positions p = posed(*model, s, Eigen::VectorXf::Zero(model->num_expressions()));
  const FaceLayer layer = reshade_face(s.frame, p, p, s.face.triangles, s.lighting, s.camera);
  ASSERT_GT(cv::countNonZero(layer.mask), 2000);
  cv::Mat out = s.frame.clone();
  composite_layer(out, layer);
  cv::Mat d;
  cv::absdiff(out, s.frame, d);
  double worst = 0;
  cv::minMaxLoc(d.reshape(1), nullptr, &worst);
  EXPECT_LE(worst, 1.0);
}

TEST(FaceReshading, ASmileChangesTheMouthCornersNotTheForehead) {
  FACECAP_REQUIRE_MODEL(model);
  const Scene s = make_scene(*model);
  Eigen::VectorXf smile = Eigen::VectorXf::Zero(model->num_expressions());
  smile[expression(*model, "mouthSmile_L")] = 1;
  smile[expression(*model, "mouthSmile_R")] = 1;
  const Positions before = posed(*model, s, Eigen::VectorXf::Zero(model->num_expressions()));
  const Positions after = posed(*model, s, smile);
  const FaceLayer layer = reshade_face(s.frame, before, after, s.face.triangles, s.lighting, s.camera);
  cv::Mat out = s.frame.clone();
  composite_layer(out, layer);
  auto change_near = [&](int vertex) {
    const Vec2f q = s.camera.project(Vec3f(after.col(vertex)));
    const cv::Rect r = cv::Rect(int(q.x()) - 6, int(q.y()) - 6, 13, 13) & cv::Rect(0, 0, out.cols, out.rows);
    cv::Mat d;
    cv::absdiff(out(r), s.frame(r), d);
    return cv::mean(d)[0];
  };
  const auto& lm = model->landmarks.vertices;
  EXPECT_GT(change_near(lm[48]), 5.0);  // mouth corners moved: the texture there moved with them
  EXPECT_GT(change_near(lm[54]), 5.0);
  EXPECT_LT(change_near(lm[19]), 1.0);  // brows: untouched
  EXPECT_LT(change_near(lm[24]), 1.0);
}

}  // namespace facecap
