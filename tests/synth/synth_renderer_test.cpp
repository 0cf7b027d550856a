#include "facecap/synth/synth_renderer.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "facecap/core/temp_dir.hpp"
#include "facecap/core/uv_texel.hpp"
#include "facecap/detect/upright_view.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/synthetic_mark.hpp"
#include "facecap/synth/skin_albedo.hpp"
#include "facecap/synth/synthesize.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

SynthOptions small_options() {
  SynthOptions o;
  o.frames = 8;
  o.width = 320;
  o.height = 240;
  o.seed = 11;
  return o;
}

// For looking at the eyes: a 960x540 performance without sensor noise, and
// its first frame with the expression cleared (eyes open).
struct EyesOpenShot {
  SynthPerformance performance;
  SynthFrame frame;
};

EyesOpenShot eyes_open_shot(const FaceModel& model) {
  SynthOptions o = small_options();
  o.width = 960;
  o.height = 540;
  o.noise_sigma = 0;
  EyesOpenShot shot{make_performance(model, o), {}};
  shot.frame = shot.performance.frames[0];
  shot.frame.expression.setZero();
  return shot;
}

}  // namespace

TEST(SynthRenderer, TruthLandmarksAreProjectedLandmarkVertices) {
  FACECAP_REQUIRE_MODEL(model);
  const SynthPerformance p = make_performance(*model, small_options());
  const SynthRenderer r(*model, p);
  for (const SynthFrame& f : p.frames) {
    const Landmarks lm = r.landmarks(f);
    const Landmarks fixed = r.landmark_vertex_projections(f);
    for (int i = 17; i < kNumLandmarks; ++i) EXPECT_LT((lm[i] - fixed[i]).norm(), 1e-3f);
    EXPECT_LT((lm[8] - fixed[8]).norm(), 1e-3f);  // the chin does not slide
    // The face is about 45% of the image high, so the eye corners are tens of pixels apart.
    EXPECT_GT(outer_eye_distance(lm), 40.0f);
    EXPECT_LT(outer_eye_distance(lm), 120.0f);
  }
}

TEST(SynthRenderer, DrawsTheFaceWhereTheLandmarksAre) {
  FACECAP_REQUIRE_MODEL(model);
  const SynthPerformance p = make_performance(*model, small_options());
  const SynthRenderer r(*model, p);
  std::mt19937_64 rng(1);
  const cv::Mat img = r.render(p.frames[0], rng);
  ASSERT_EQ(img.cols, 320);
  const Landmarks lm = r.landmarks(p.frames[0]);
  const cv::Vec3b nose = img.at<cv::Vec3b>(int(lm[30].y()), int(lm[30].x()));
  const cv::Vec3b corner = img.at<cv::Vec3b>(3, 3);
  // Skin is redder than the blue-grey background.
  EXPECT_GT(int(nose[2]) - int(nose[0]), 10);
  EXPECT_LT(int(corner[2]) - int(corner[0]), 10);
}

// A camera rolled about its axis (half a turn, and a quarter turn either
// way) sees the scene turned, lit as before: the render is the upright one
// turned (mean difference over the face under 0.01 grey levels; 13.8 at 180
// degrees with the lighting left the camera's, and 13.5-13.7 at +-90 with it
// turned the camera's way rather than the viewer's, which a half turn cannot
// tell apart) and so are its landmarks, the jaw's silhouette points included (its
// vertices are chosen along the head's own left-right axis,
// jaw_contour.hpp). What `eval track --roll` measures the tracker on.
TEST(SynthRenderer, ARolledCameraSeesTheSceneTurned) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o = small_options();
  o.noise_sigma = 0;
  o.height = 320;  // square, so that a quarter turn keeps the face in the frame
  const SynthPerformance upright = make_performance(*model, o);
  const SynthRenderer ru(*model, upright);
  std::mt19937_64 rng(1);
  for (const double degrees : {180.0, 90.0, -90.0}) {
    SynthOptions rolled_options = o;
    rolled_options.camera_roll_deg = degrees;
    const SynthPerformance rolled = make_performance(*model, rolled_options);
    const SynthRenderer rr(*model, rolled);
    // Clockwise in the image (y down) about the principal point.
    const double t = degrees * 3.14159265358979323846 / 180.0;
    const Eigen::Matrix2f turn = Eigen::Rotation2Df(float(t)).toRotationMatrix();
    const Vec2f pp(float(upright.camera.cx), float(upright.camera.cy));
    auto turned = [&](const Vec2f& p) -> Vec2f { return pp + turn * (p - pp); };
    for (int f : {0, 5}) {
      const Landmarks lu = ru.landmarks(upright.frames[f]), lr = rr.landmarks(rolled.frames[f]);
      for (int i = 0; i < kNumLandmarks; ++i)
        EXPECT_LT((lr[i] - turned(lu[i])).norm(), 1e-2f) << degrees << " " << f << " " << i;
      EXPECT_NEAR(std::remainder(roll_degrees(lr) - roll_degrees(lu) - float(degrees), 360.0f), 0.0f, 1e-2f);
      const cv::Mat iu = ru.render(upright.frames[f], rng), ir = rr.render(rolled.frames[f], rng);
      // The face's pixels, compared where the turn lands them.
      std::vector<cv::Point> hull;
      cv::convexHull(std::vector<cv::Point>{cv::Point(lu[0].x(), lu[0].y()), cv::Point(lu[8].x(), lu[8].y()),
                                            cv::Point(lu[16].x(), lu[16].y()), cv::Point(lu[19].x(), lu[19].y()),
                                            cv::Point(lu[24].x(), lu[24].y())},
                     hull);
      cv::Mat face(iu.size(), CV_8U, cv::Scalar(0));
      cv::fillConvexPoly(face, hull, cv::Scalar(255));
      double difference = 0;
      int n = 0;
      for (int y = 0; y < iu.rows; ++y)
        for (int x = 0; x < iu.cols; ++x) {
          if (!face.at<uchar>(y, x)) continue;
          const Vec2f q = turned(Vec2f(float(x), float(y)));
          cv::Mat patch;
          cv::getRectSubPix(ir, cv::Size(1, 1), cv::Point2f(q.x(), q.y()), patch);
          const cv::Vec3b a = iu.at<cv::Vec3b>(y, x), b = patch.at<cv::Vec3b>(0, 0);
          for (int c = 0; c < 3; ++c) difference += std::abs(int(a[c]) - int(b[c]));
          n += 3;
        }
      ASSERT_GT(n, 3000);
      EXPECT_LT(difference / n, 2.0) << "mean grey-level difference over the face, " << degrees << " degrees, frame "
                                     << f;
    }
  }
}

// The iris is a flat disc behind the cornea: evenly lit across, though
// the cornea's sphere it is painted on faces up at its top and down at its
// foot. Lit hard from above (the renders' key light always is, from 11-46
// degrees), the sphere's shading made the iris's lower band 13.2 levels
// darker than its upper (mean of both eyes, this frame), which drew the iris
// search down; shaded flat, 0.05.
TEST(SynthRenderer, TheIrisIsEvenlyLit) {
  FACECAP_REQUIRE_MODEL(model);
  const EyesOpenShot shot = eyes_open_shot(*model);
  const SynthPerformance& p = shot.performance;
  SynthFrame f = shot.frame;
  f.gaze_deg.setZero();
  f.lighting.setZero();
  f.lighting[0] = 0.7;
  f.lighting[2] = 0.5;  // light from above, as the renders' key light always is
  const SynthRenderer r(*model, p);
  std::mt19937_64 rng(1);
  cv::Mat grey;
  cv::cvtColor(r.render(f, rng), grey, cv::COLOR_BGR2GRAY);
  double difference = 0;
  for (int eye = 0; eye < 2; ++eye) {
    const Vec2d c = r.iris_centre(f, eye);
    const Vec3d centre = f.pose.model_to_camera_rotation() * r.eyeballs().centre[eye] + f.pose.translation;
    const double radius = p.camera.focal * kIrisRadiusCm / centre.z();
    ASSERT_GT(radius, 5.0);
    // Bands a quarter to 0.4 of the radius above and below the centre,
    // beside the pupil (0.22 / 0.585 of the radius) and inside the rim.
    double band[2] = {0, 0};
    int count[2] = {0, 0};
    for (int y = int(c.y() - radius); y <= int(c.y() + radius); ++y)
      for (int x = int(c.x() - radius); x <= int(c.x() + radius); ++x) {
        const double dx = x - c.x(), dy = y - c.y();
        if (std::abs(dy) < 0.25 * radius || std::abs(dy) > 0.4 * radius) continue;
        if (std::abs(dx) < 0.45 * radius || std::hypot(dx, dy) > 0.8 * radius) continue;
        band[dy > 0] += grey.at<uint8_t>(y, x);
        ++count[dy > 0];
      }
    ASSERT_GT(count[0], 4);
    ASSERT_GT(count[1], 4);
    difference += (band[0] / count[0] - band[1] / count[1]) / 2;
  }
  EXPECT_LT(std::abs(difference), 1.0) << "upper band minus lower band, grey levels";
}

// The eyeballs turn with the gaze: the pupil (the render's darkest pixels)
// is where the turned eyeball's front projects, and iris_centre() (the iris
// ring's centre, a little deeper) is beside it.
TEST(SynthRenderer, TheIrisesTurnWithTheGaze) {
  FACECAP_REQUIRE_MODEL(model);
  const EyesOpenShot shot = eyes_open_shot(*model);
  const SynthPerformance& p = shot.performance;
  SynthFrame f = shot.frame;
  const SynthRenderer r(*model, p);
  std::mt19937_64 rng(1);
  std::array<Vec2d, 2> left_gaze;
  for (const double yaw : {-25.0, 25.0}) {
    f.gaze_deg = Vec2d(yaw, 5.0);
    cv::Mat grey;
    cv::cvtColor(r.render(f, rng), grey, cv::COLOR_BGR2GRAY);
    for (int eye = 0; eye < 2; ++eye) {
      const Vec2d iris = r.iris_centre(f, eye);
      const EyeballGeometry& eyes = r.eyeballs();
      const Vec3d front = eyes.centre[eye] + eyes.radius[eye] * turned_axis(eyes, eye, f.gaze_deg.x(), f.gaze_deg.y());
      const Vec2d pupil = p.camera.project(Vec3d(f.pose.model_to_camera_rotation() * front + f.pose.translation));
      // The iris's centre lies on the axis, radius - painted_iris_depth
      // (2-3 mm) behind the pupil: its image no farther from the pupil's
      // than that length seen side-on.
      const double depth = (f.pose.model_to_camera_rotation() * front + f.pose.translation).z();
      EXPECT_LT((pupil - iris).norm(), p.camera.focal * (eyes.radius[eye] - r.painted_iris_depth(eye)) / depth);
      Vec2d sum = Vec2d::Zero();
      int n = 0;
      for (int y = int(iris.y()) - 15; y <= int(iris.y()) + 15; ++y)
        for (int x = int(iris.x()) - 15; x <= int(iris.x()) + 15; ++x)
          if (grey.at<uint8_t>(y, x) < 20) sum += Vec2d(x, y), ++n;
      ASSERT_GT(n, 10) << "yaw " << yaw << " eye " << eye;
      // The pupil is painted on the eyeball's vertices, about 1 mm (2 px here)
      // apart, so its drawn outline is ragged by about that.
      EXPECT_LT((sum / n - pupil).norm(), 2.0) << "yaw " << yaw << " eye " << eye;
      if (eye == 1) left_gaze[yaw > 0] = iris;
    }
  }
  // Looking toward the subject's left moves the irises to the image's right.
  EXPECT_GT(left_gaze[1].x() - left_gaze[0].x(), 6.0);
}

// iris_centre() is where the painted iris shows: the eyeballs alone,
// rasterised at 4x, put the centre of the painted area within 0.45 px of it
// in every frame (seed 3). With the sphere's iris_depth in its place (the
// cornea bulges past it, so the painted rim lies 1.3 mm nearer the
// eyeball's centre), up to 1.0 px.
TEST(SynthRenderer, TheIrisCentreIsWhereThePaintedIrisShows) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o;
  o.frames = 20;
  o.seed = 3;
  const SynthPerformance p = make_performance(*model, o);
  const SynthRenderer r(*model, p);
  const std::vector<Triangle> all = model->full_mesh().triangles;
  constexpr int kScale = 4;
  const PinholeCamera camera = p.camera.resized(kScale);
  RasterBuffers buffers;
  buffers.resize(o.width * kScale, o.height * kScale);
  for (int eye = 0; eye < 2; ++eye) {
    const Region& eyeball = eyeball_region(eye);
    std::vector<Triangle> triangles;
    for (const Triangle& t : all)
      if (t[0] >= eyeball.first_vertex && t[0] <= eyeball.last_vertex) triangles.push_back(t);
    std::vector<float> painted(model->num_vertices, 0.0f);
    for (const int v : r.appearance().iris_vertices[eye]) painted[v] = 1.0f;
    for (const SynthFrame& f : p.frames) {
      Positions head = model->evaluate(p.identity, f.expression);
      turn_eyeballs(r.eyeballs(), f.gaze_deg.x(), f.gaze_deg.y(), head);
      rasterize(to_camera(head, f.pose), triangles, camera, buffers);
      Vec2d sum = Vec2d::Zero();
      int n = 0;
      for (int y = buffers.drawn_y0; y < buffers.drawn_y1; ++y)
        for (int x = buffers.drawn_x0; x < buffers.drawn_x1; ++x) {
          const size_t i = size_t(y) * buffers.width + x;
          if (buffers.triangle[i] < 0) continue;
          const Triangle& t = triangles[buffers.triangle[i]];
          const Vec2f b = buffers.bary[i];
          if ((1 - b.x() - b.y()) * painted[t[0]] + b.x() * painted[t[1]] + b.y() * painted[t[2]] > 0.5f)
            sum += Vec2d(x, y), ++n;
        }
      ASSERT_GT(n, 100);
      const Vec2d shown = (sum / n - Vec2d::Constant(0.5 * (kScale - 1))) / kScale;
      EXPECT_LT((shown - r.iris_centre(f, eye)).norm(), 0.6) << "frame " << f.index << " eye " << eye;
    }
  }
}

// The 300-W annotation, which dlib learnt, puts the brow points on the
// brow's upper edge: the painted brow lies below its landmark vertices (with
// the brow centred on them, dlib's brow points sat 0.058 / 0.077 of the eye
// distance from the truth on seeds 1 / 2; with this, 0.036 / 0.043).
TEST(SkinAlbedo, BrowsHangBelowTheirLandmarkVertices) {
  FACECAP_REQUIRE_MODEL(model);
  const int size = 1024;
  const Vec3f tone(0.8f, 0.6f, 0.5f);
  const SynthAppearance a = paint_appearance(*model, tone, 1, size);
  const std::vector<Vec2f> uv = per_vertex_uvs(model->region_mesh(regions::kFace));
  auto px = [&](int landmark) { return uv_to_texel(uv[model->landmarks.vertices[landmark]], size); };
  auto brightness = [&](const Vec2f& p) {
    const cv::Vec3f c = a.face_texture.at<cv::Vec3f>(int(std::lround(p.y())), int(std::lround(p.x())));
    return (c[0] + c[1] + c[2]) / 3.0f;
  };
  const float skin = tone.mean(), eye_px = (px(36) - px(45)).norm();
  for (int i = 17; i <= 26; ++i) {
    Vec2f eye = Vec2f::Zero();
    for (int k = 0; k < 6; ++k) eye += px((i < 22 ? 36 : 42) + k) / 6.0f;
    const Vec2f down = (eye - px(i)).normalized();
    EXPECT_LT(brightness(px(i) + 0.035f * eye_px * down), 0.6f * skin) << "brow point " << i;  // in the brow
    EXPECT_GT(brightness(px(i) - 0.03f * eye_px * down), 0.8f * skin) << "brow point " << i;   // above it
  }
}

// A given texture (a real portrait's skin, SynthOptions::face_texture) is
// the face's skin: each face vertex takes the texel at its UV (checked on a
// texture whose colour encodes the UV, so a flipped or shifted lookup
// fails), and the rest of the head takes the face's mean colour rather than
// the painted tone, so no seam is drawn where the face region ends.
TEST(SkinAlbedo, AGivenTextureIsTheFacesSkin) {
  FACECAP_REQUIRE_MODEL(model);
  const int given = 512, size = 256;
  cv::Mat texture(given, given, CV_32FC3);
  for (int y = 0; y < given; ++y)
    for (int x = 0; x < given; ++x) {
      const float u = float(x) / (given - 1), v = 1.0f - float(y) / (given - 1);
      texture.at<cv::Vec3f>(y, x) = cv::Vec3f(0.2f + 0.6f * u, 0.2f + 0.6f * v, 0.5f);  // BGR
    }
  const Vec3f painted_tone(0.9f, 0.1f, 0.1f);
  const SynthAppearance a = paint_appearance(*model, painted_tone, 1, size, texture);
  ASSERT_EQ(a.face_texture.rows, size);
  const std::vector<Vec2f> uv = per_vertex_uvs(model->region_mesh(regions::kFace));
  float worst = 0;
  for (int v = 0; v < regions::kFace.num_vertices(); ++v) {
    const Vec3f expected(0.5f, 0.2f + 0.6f * uv[v].y(), 0.2f + 0.6f * uv[v].x());  // RGB
    worst = std::max(worst, (a.vertex_albedo.col(v) - expected).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 0.01f);  // within the resampling of a linear ramp
  const Vec3f face_mean = a.vertex_albedo.leftCols(regions::kNarrowFace.num_vertices()).rowwise().mean();
  const Vec3f head = a.vertex_albedo.col(regions::kHeadAndNeck.first_vertex);
  EXPECT_LT((head - face_mean).norm(), 1e-5f);
  EXPECT_GT((head - painted_tone).norm(), 0.3f);
  // Out-of-range texels are clamped to what an albedo can be.
  cv::Mat bright(64, 64, CV_32FC3, cv::Scalar(1.5, -0.2, 0.5));
  const SynthAppearance b = paint_appearance(*model, painted_tone, 1, 64, bright);
  EXPECT_NEAR(b.vertex_albedo(0, 0), 0.5f, 1e-6f);  // R
  EXPECT_NEAR(b.vertex_albedo(1, 0), 0.0f, 1e-6f);  // G
  EXPECT_NEAR(b.vertex_albedo(2, 0), 1.0f, 1e-6f);  // B
}

TEST(SynthRenderer, DetailDisplacesTheSurfaceAlongItsNormals) {
  FACECAP_REQUIRE_MODEL(model);
  SynthOptions o = small_options();
  o.noise_sigma = 0;
  const SynthPerformance plain = make_performance(*model, o);
  o.detail = true;
  const SynthPerformance detailed = make_performance(*model, o);
  const SynthRenderer rp(*model, plain), rd(*model, detailed);
  ASSERT_NE(rd.detail_mesh(), nullptr);
  float max_d = 0;
  for (float d : rd.detail_displacement()) max_d = std::max(max_d, std::abs(d));
  EXPECT_GT(max_d, 0.03f);  // wrinkles of a few tenths of a millimetre...
  EXPECT_LT(max_d, 0.15f);  // ...not centimetres
  // The detailed surface is the subdivided coarse surface moved by d along its normal.
  const Positions fine = rd.detailed_face(detailed.frames[0]);
  const Positions coarse = rd.detail_mesh()->prolong(rp.detailed_face(plain.frames[0]));
  ASSERT_EQ(fine.cols(), coarse.cols());
  double max_err = 0;
  for (Eigen::Index v = 0; v < fine.cols(); ++v) {
    max_err = std::max(max_err,
                       double(std::abs((fine.col(v) - coarse.col(v)).norm() - std::abs(rd.detail_displacement()[v]))));
  }
  EXPECT_LT(max_err, 1e-4);
  // And it shows in the image: the face pixels change, the background does not.
  std::mt19937_64 r1(1), r2(1);
  cv::Mat a, b, diff;
  rp.render(plain.frames[0], r1).convertTo(a, CV_32F);
  rd.render(detailed.frames[0], r2).convertTo(b, CV_32F);
  cv::absdiff(a, b, diff);
  const Box box = bounding_box(rp.landmarks(plain.frames[0]));
  const cv::Rect face(int(box.x), int(box.y), int(box.width), int(box.height));
  double max_face = 0;
  cv::minMaxLoc(diff(face).reshape(1), nullptr, &max_face);
  EXPECT_GT(max_face, 10.0);
  EXPECT_LT(cv::mean(diff(cv::Rect(0, 0, 20, 20)))[0], 0.5);
}

TEST(Synthesize, WritesVideoTruthAlbedoAndTheSyntheticMarks) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  SynthOptions o = small_options();
  o.frames = 5;
  const SynthJobResult r = synthesize(*model, o, dir.path(), true);
  auto video = open_input(r.video.string());
  EXPECT_EQ(video->info().frames, 5);
  EXPECT_EQ(video->info().width, 320);
  EXPECT_TRUE(std::filesystem::exists(r.truth));
  EXPECT_TRUE(std::filesystem::exists(r.albedo));
  EXPECT_TRUE(std::filesystem::exists(sidecar_path(r.video)));
  EXPECT_EQ(r.ground_truth.landmarks.size(), 5u);
}

// A test that needs only the start of a long performance renders only that:
// the same frames and truth (the frames alike up to the encoding: measured
// 44-46 dB, since x264 looks ahead to the frames that follow).
TEST(Synthesize, TheFirstFramesOfAPerformanceAreRenderedAsInTheWhole) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  SynthOptions o = small_options();
  const SynthJobResult whole = synthesize(*model, o, dir.path() / "whole", true);
  o.render_frames = 3;
  const SynthJobResult start = synthesize(*model, o, dir.path() / "start", true);
  ASSERT_EQ(start.ground_truth.performance.frames.size(), 3u);
  ASSERT_EQ(start.ground_truth.landmarks.size(), 3u);
  auto a = open_input(whole.video.string());
  auto b = open_input(start.video.string());
  EXPECT_EQ(b->info().frames, 3);
  for (int f = 0; f < 3; ++f) {
    Frame fa, fb;
    ASSERT_TRUE(a->read(fa));
    ASSERT_TRUE(b->read(fb));
    EXPECT_GT(cv::PSNR(fa.image, fb.image), 40.0) << f;
    EXPECT_EQ(start.ground_truth.performance.frames[size_t(f)].pose.translation,
              whole.ground_truth.performance.frames[size_t(f)].pose.translation);
    EXPECT_EQ(start.ground_truth.landmarks[size_t(f)], whole.ground_truth.landmarks[size_t(f)]);
  }
  Frame past_end;
  EXPECT_FALSE(b->read(past_end));
  EXPECT_EQ(read_truth(start.truth).performance.options.render_frames, 3);
}

}  // namespace facecap
