#include "facecap/synth/skin_albedo.hpp"

#include <opencv2/imgproc.hpp>
#include <random>

#include "facecap/core/image_sampling.hpp"
#include "facecap/detect/landmarks.hpp"
#include "facecap/model/eyeballs.hpp"

namespace facecap {

namespace {

cv::Scalar bgr(const Vec3f& rgb) { return cv::Scalar(rgb.z(), rgb.y(), rgb.x()); }

// The painted skin: a base tone with darker brows, lips, lid lines and
// nostrils placed from the UVs of the landmark vertices.
cv::Mat painted_skin(const FaceModel& model, const std::vector<Vec2f>& uv, const Vec3f& tone, std::mt19937_64& rng,
                     int size) {
  auto to_px = [&](int vertex) {
    const Vec2f t = uv_to_texel(uv[vertex], size);
    return cv::Point2f(t.x(), t.y());
  };
  auto landmark_px = [&](int i) { return to_px(model.landmarks.vertices[i]); };

  // Base tone with gentle low-frequency variation.
  cv::Mat tex(size, size, CV_32FC3, bgr(tone));
  cv::Mat variation(size / 32, size / 32, CV_32F);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (int y = 0; y < variation.rows; ++y)
    for (int x = 0; x < variation.cols; ++x) variation.at<float>(y, x) = 0.04f * normal(rng);
  cv::resize(variation, variation, cv::Size(size, size), 0, 0, cv::INTER_CUBIC);
  cv::GaussianBlur(variation, variation, cv::Size(0, 0), size / 64.0);
  std::vector<cv::Mat> ch;
  cv::split(tex, ch);
  for (auto& c : ch) c = c.mul(1.0f + variation);
  cv::merge(ch, tex);

  const float eye_px = float(cv::norm(landmark_px(36) - landmark_px(45)));
  auto eye_centre = [&](int side) {  // 0: landmarks 36-41, 1: 42-47
    cv::Point2f c(0, 0);
    for (int i = first_eye_landmark(side); i < first_eye_landmark(side) + kEyeLandmarks; ++i)
      c += landmark_px(i) / float(kEyeLandmarks);
    return c;
  };
  const auto polyline = [&](int from, int to, bool closed, const Vec3f& colour, float width) {
    std::vector<cv::Point> pts;
    for (int i = from; i <= to; ++i) pts.push_back(landmark_px(i));
    cv::polylines(tex, pts, closed, bgr(colour), std::max(1, int(width)), cv::LINE_AA);
  };
  const auto fill = [&](int from, int to, const Vec3f& colour) {
    std::vector<cv::Point> pts;
    for (int i = from; i <= to; ++i) pts.push_back(landmark_px(i));
    cv::fillPoly(tex, std::vector<std::vector<cv::Point>>{pts}, bgr(colour), cv::LINE_AA);
  };
  // Soft shading around the eyes, cheeks with a touch of red.
  cv::Mat soft(size, size, CV_32FC3, cv::Scalar::all(0));
  for (int side : {0, 1}) {
    cv::ellipse(soft, eye_centre(side), cv::Size2f(0.3f * eye_px, 0.17f * eye_px), 0, 0, 360, cv::Scalar::all(-0.18),
                -1);
  }
  cv::GaussianBlur(soft, soft, cv::Size(0, 0), 0.05 * eye_px);
  tex = tex.mul(cv::Scalar::all(1.0) + soft);

  const Vec3f brow = tone.cwiseProduct(Vec3f(0.30f, 0.26f, 0.24f));
  const Vec3f lip = tone.cwiseProduct(Vec3f(0.95f, 0.62f, 0.62f));
  const Vec3f lid = tone.cwiseProduct(Vec3f(0.35f, 0.3f, 0.3f));
  // The 300-W annotation puts the brow points on the brow's upper edge, so
  // the brow is painted below its landmark vertices, toward the eye.
  const float brow_width = 0.07f * eye_px;
  for (int side : {0, 1}) {
    const cv::Point2f eye = eye_centre(side);
    std::vector<cv::Point> pts;
    for (int i = 17 + 5 * side; i <= 21 + 5 * side; ++i) {
      const cv::Point2f p = landmark_px(i), d = eye - p;
      pts.push_back(p + d * (0.5f * brow_width / std::max(1.0f, float(cv::norm(d)))));
    }
    cv::polylines(tex, pts, false, bgr(brow), std::max(1, int(brow_width)), cv::LINE_AA);
  }
  fill(48, 59, lip);
  polyline(48, 59, true, lip * 0.9f, 0.02f * eye_px);
  polyline(36, 41, true, lid, 0.025f * eye_px);
  polyline(42, 47, true, lid, 0.025f * eye_px);
  for (int n : {31, 35}) cv::circle(tex, landmark_px(n), int(0.03f * eye_px), bgr(tone * 0.35f), -1, cv::LINE_AA);
  cv::GaussianBlur(tex, tex, cv::Size(0, 0), std::max(0.8, size / 700.0));
  return tex;
}

// A given skin texture at `size` texels, clamped to [0, 1].
cv::Mat given_skin(const cv::Mat& texture, int size) {
  cv::Mat tex;
  cv::resize(texture, tex, cv::Size(size, size), 0, 0, texture.cols > size ? cv::INTER_AREA : cv::INTER_LINEAR);
  return cv::min(cv::max(tex, 0.0f), 1.0f);
}

}  // namespace

SynthAppearance paint_appearance(const FaceModel& model, const Vec3f& painted_tone, uint64_t seed, int size,
                                 const cv::Mat& face_texture) {
  SynthAppearance out;
  const TriangleMesh face = model.region_mesh(regions::kFace);
  const std::vector<Vec2f> uv = per_vertex_uvs(face);
  std::mt19937_64 rng(seed ^ 0x5eed5eedull);
  out.face_texture =
      face_texture.empty() ? painted_skin(model, uv, painted_tone, rng, size) : given_skin(face_texture, size);

  // Per-vertex albedo of the whole head.
  out.vertex_albedo = Positions(3, model.num_vertices);
  out.drawn.assign(model.num_vertices, true);
  Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
  auto paint_range = [&](const Region& r, const Vec3f& c) {
    for (int v = r.first_vertex; v <= r.last_vertex; ++v) out.vertex_albedo.col(v) = c;
  };
  for (int v = 0; v < regions::kFace.num_vertices(); ++v)
    out.vertex_albedo.col(v) = sample_uv_rgb(out.face_texture, uv[v]);
  // A given texture's head and neck take the mean colour of its narrow face.
  const Vec3f tone = face_texture.empty()
                         ? painted_tone
                         : Vec3f(out.vertex_albedo.leftCols(regions::kNarrowFace.num_vertices()).rowwise().mean());
  paint_range(regions::kHeadAndNeck, tone);
  paint_range(regions::kMouthSocket, Vec3f(0.25f, 0.08f, 0.08f));
  paint_range(regions::kEyeSocketLeft, tone * 0.3f);
  paint_range(regions::kEyeSocketRight, tone * 0.3f);
  paint_range(regions::kGumsAndTongue, Vec3f(0.55f, 0.2f, 0.2f));
  paint_range(regions::kTeeth, Vec3f(0.85f, 0.82f, 0.74f));
  const Vec3f iris = Vec3f(0.25f, 0.16f, 0.1f) * float(0.6 + 0.8 * std::uniform_real_distribution<double>()(rng));
  // Pupil and iris: discs about the eyeball's front-most vertex, as wide as
  // eyeballs.hpp says an iris is.
  const EyeballGeometry eyes = eyeball_geometry(model, Eigen::VectorXd());
  for (int eye = 0; eye < 2; ++eye) {
    const Region& eyeball = eyeball_region(eye);
    const Vec3f centre = eyes.centre[eye].cast<float>();
    const Vec3f axis = eyes.rest_axis[eye].cast<float>();
    for (int v = eyeball.first_vertex; v <= eyeball.last_vertex; ++v) {
      const Vec3f offset = neutral.col(v) - centre;
      const float from_axis = (offset - offset.dot(axis) * axis).norm();
      const bool front = offset.dot(axis) > 0.0f;
      const bool in_iris = front && from_axis < float(kIrisRadiusCm);
      out.vertex_albedo.col(v) = in_iris && from_axis < 0.22f ? Vec3f(0.02f, 0.02f, 0.02f)
                                 : in_iris                    ? iris
                                                              : Vec3f(0.85f, 0.82f, 0.8f);
      if (in_iris) out.iris_vertices[eye].push_back(v);
    }
  }
  for (int v = regions::kEyeExtras.first_vertex; v <= regions::kEyeExtras.last_vertex; ++v) {
    out.vertex_albedo.col(v) = Vec3f::Zero();
    out.drawn[v] = false;
  }
  return out;
}

}  // namespace facecap
