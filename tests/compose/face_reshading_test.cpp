#include "facecap/compose/face_reshading.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/compose/face_layer.hpp"
#include "facecap/compose/surface_exposure.hpp"
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

// The shading ratio in full where the surface faces the camera, none at
// all edge-on, and its power between (a smoothstep of the facing).
TEST(FaceReshading, TheShadingRatioFadesOutTowardsEdgeOn) {
  EXPECT_FLOAT_EQ(shading_ratio(0.2f, 0.3f, 0.9f), 1.5f);
  EXPECT_FLOAT_EQ(shading_ratio(0.2f, 0.3f, kFacing), 1.5f);
  EXPECT_FLOAT_EQ(shading_ratio(0.1f, 0.4f, 0.9f), 2.0f);   // clamped
  EXPECT_FLOAT_EQ(shading_ratio(0.4f, 0.1f, 0.9f), 0.5f);   // clamped
  EXPECT_FLOAT_EQ(shading_ratio(0.04f, 0.3f, 0.9f), 1.0f);  // no shading to divide by
  const float halfway = 0.5f * (kFacing + kGrazingFacing);
  EXPECT_NEAR(shading_ratio(0.1f, 0.2f, halfway), std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(shading_ratio(0.2f, 0.1f, halfway), std::sqrt(0.5f), 1e-5f);
  EXPECT_FLOAT_EQ(shading_ratio(0.1f, 0.2f, kGrazingFacing), 1.0f);
  EXPECT_FLOAT_EQ(shading_ratio(0.1f, 0.2f, -0.3f), 1.0f);
  float last = 1.0f;
  for (float facing = kGrazingFacing; facing <= kFacing; facing += 0.01f) {
    const float r = shading_ratio(0.1f, 0.2f, facing);
    EXPECT_GE(r, last) << facing;
    last = r;
  }
}

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

// Closing the eyes unfolds the lids, which ICT folds away while the eye is
// open: the frame shows them edge-on. A highlight there (a white spot where
// the least seen lid vertex in view lay in the frame) is not stretched over
// the closed lid: that vertex's pixel takes its colour from the skin around.
TEST(FaceReshading, AClosingLidDoesNotStretchWhatTheFrameSawEdgeOn) {
  FACECAP_REQUIRE_MODEL(model);
  Scene s = make_scene(*model);
  Eigen::VectorXf blink = Eigen::VectorXf::Zero(model->num_expressions());
  blink[expression(*model, "eyeBlink_L")] = 1;
  blink[expression(*model, "eyeBlink_R")] = 1;
  const Positions open = posed(*model, s, Eigen::VectorXf::Zero(model->num_expressions()));
  const Positions closed = posed(*model, s, blink);
  const std::vector<float> exposure = vertex_exposure(open, closed, s.face.triangles, s.camera);
  // The least seen vertex whose own triangle is what the closed face shows at its pixel.
  RasterBuffers shown;
  shown.resize(s.frame.cols, s.frame.rows);
  rasterize(closed, s.face.triangles, s.camera, shown);
  auto in_view = [&](int v) {
    const Vec2f q = s.camera.project(Vec3f(closed.col(v)));
    const int x = cvRound(q.x()), y = cvRound(q.y());
    if (x < 0 || y < 0 || x >= shown.width || y >= shown.height || !shown.covered(x, y)) return false;
    const Triangle& t = s.face.triangles[shown.triangle[size_t(y) * shown.width + x]];
    return std::find(t.begin(), t.end(), v) != t.end();
  };
  int lid = -1;
  for (int v = 0; v < int(exposure.size()); ++v)
    if (in_view(v) && (lid < 0 || exposure[v] < exposure[lid])) lid = v;
  ASSERT_GE(lid, 0);
  ASSERT_LT(exposure_trust(exposure[lid]), 0.25f) << exposure[lid];
  const Vec2f then = s.camera.project(Vec3f(open.col(lid))), now = s.camera.project(Vec3f(closed.col(lid)));
  ASSERT_GT((now - then).norm(), 2.0f) << "the lid moves as it closes";
  cv::circle(s.frame, cv::Point(cvRound(then.x()), cvRound(then.y())), 2, cv::Scalar(255, 255, 255), cv::FILLED);
  const FaceLayer layer = reshade_face(s.frame, open, closed, s.face.triangles, s.lighting, s.camera);
  const cv::Point at(cvRound(now.x()) - layer.box.x, cvRound(now.y()) - layer.box.y);
  ASSERT_GT(layer.mask.at<uchar>(at), 0);
  const cv::Vec3b lid_colour = layer.colour.at<cv::Vec3b>(at);
  EXPECT_LT(std::max({lid_colour[0], lid_colour[1], lid_colour[2]}), 200) << lid_colour;
}

}  // namespace facecap
