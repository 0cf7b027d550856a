#include "facecap/synth/synth_renderer.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/render/shading.hpp"
#include "facecap/synth/sensor_noise.hpp"
#include "facecap/synth/wrinkles.hpp"

namespace facecap {

namespace {

// The painted iris's rim on an identity's eyeball: the mean depth, along the
// eye's rest axis from its centre, of the midpoints of the eyeball's edges
// between a painted vertex and an unpainted one on the front (where the
// interpolated paint crosses half-way). Only the depth is taken: the mean
// of the midpoints themselves leans sideways with the mesh's uneven spacing
// around the rim (0.5 mm on seed 2, which put the truth up to 1 px off the
// painted area's centre), while the rim is centred on the axis by how it
// was painted (skin_albedo.cpp).
double painted_rim_depth(const FaceModel& model, const Eigen::VectorXf& identity, const EyeballGeometry& eyes, int eye,
                         const std::vector<int>& painted) {
  const Region& region = eyeball_region(eye);
  const Eigen::VectorXf shape = model.identity_shape(identity, region);
  const Eigen::Map<const Positions> eyeball(shape.data(), 3, region.num_vertices());
  std::vector<char> is_painted(model.num_vertices, 0);
  for (const int v : painted) is_painted[v] = 1;
  double depth = 0;
  int edges = 0;
  for (const Polygon& polygon : model.polygons) {
    const auto on_eyeball = [&](int v) { return v >= region.first_vertex && v <= region.last_vertex; };
    if (!std::all_of(polygon.v.begin(), polygon.v.begin() + polygon.size(), on_eyeball)) continue;
    for (int k = 0; k < polygon.size(); ++k) {
      const int a = polygon.v[k], b = polygon.v[(k + 1) % polygon.size()];
      if (is_painted[a] == is_painted[b]) continue;
      const Vec3f midpoint = 0.5f * (eyeball.col(a - region.first_vertex) + eyeball.col(b - region.first_vertex));
      const double d = (midpoint.cast<double>() - eyes.centre[eye]).dot(eyes.rest_axis[eye]);
      if (d <= 0) continue;
      depth += d;
      ++edges;
    }
  }
  if (edges == 0) throw Error("SynthRenderer: the painted iris has no rim");
  return depth / edges;
}

}  // namespace

SynthRenderer::SynthRenderer(const FaceModel& model, const SynthPerformance& performance)
    : model_(model),
      performance_(performance),
      appearance_(paint_appearance(model, performance.skin_tone, performance.options.seed, 1024,
                                   performance.options.face_texture)),
      contour_(build_jaw_contour(model)),
      eyes_(eyeball_geometry(model, performance.identity.cast<double>())) {
  for (int eye = 0; eye < 2; ++eye)
    painted_iris_depth_[eye] =
        painted_rim_depth(model, performance.identity, eyes_, eye, appearance_.iris_vertices[eye]);
  const TriangleMesh face = model.region_mesh(regions::kFace);
  face_triangles_ = face.triangles;
  // Everything but the face polygons (drawn from the face mesh) and the
  // transparent eye overlays.
  const std::vector<Polygon> rest(model.polygons.begin() + regions::kFace.last_polygon + 1, model.polygons.end());
  for (const Triangle& t : triangulate(rest, {}, model.num_vertices).triangles) {
    if (appearance_.drawn[t[0]] && appearance_.drawn[t[1]] && appearance_.drawn[t[2]]) head_triangles_.push_back(t);
  }
  detail_ = performance.options.detail;
  if (detail_) {
    subdivision_ = subdivide_midpoint(face_triangles_, regions::kFace.num_vertices(), 2);
    Eigen::Map<const Positions> neutral(model.neutral.data(), 3, model.num_vertices);
    const Positions fine_neutral = subdivision_.prolong(Positions(neutral.leftCols(regions::kFace.num_vertices())));
    displacement_.resize(subdivision_.num_vertices);
    for (int v = 0; v < subdivision_.num_vertices; ++v) displacement_[v] = wrinkle_displacement(fine_neutral.col(v));
    const std::vector<Vec2f> fine_uv = subdivision_.prolong(per_vertex_uvs(face));
    fine_albedo_.resize(3, subdivision_.num_vertices);
    for (int v = 0; v < subdivision_.num_vertices; ++v)
      fine_albedo_.col(v) = sample_uv_rgb(appearance_.face_texture, fine_uv[v]);
  }
  // A quiet studio background: a vertical gradient with soft blotches.
  const int w = performance.options.width * kSupersample, h = performance.options.height * kSupersample;
  background_ = cv::Mat(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y) {
    const float t = float(y) / h;
    background_.row(y).setTo(cv::Scalar(0.55f - 0.15f * t, 0.5f - 0.12f * t, 0.45f - 0.1f * t));
  }
  std::mt19937_64 rng(performance.options.seed * 7919ull + 17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // Grey blotches: blurred once, on one channel (a Gaussian of some 200 px
  // at 720p supersampled, most of a render's start-up; the same values on
  // three channels took 3.7 times as long).
  cv::Mat blotch(h, w, CV_32F, cv::Scalar::all(0));
  for (int i = 0; i < 6; ++i) {
    cv::circle(blotch, cv::Point(int(u(rng) * w), int(u(rng) * h)), int((0.1f + 0.2f * u(rng)) * w),
               cv::Scalar::all(0.08f * (u(rng) - 0.5f)), -1);
  }
  cv::GaussianBlur(blotch, blotch, cv::Size(0, 0), 0.08 * w);
  cv::Mat grey;
  cv::merge(std::vector<cv::Mat>{blotch, blotch, blotch}, grey);
  background_ += grey;
}

Positions SynthRenderer::head_positions(const SynthFrame& frame) const {
  Positions head = model_.evaluate(performance_.identity, frame.expression);
  turn_eyeballs(eyes_, frame.gaze_deg.x(), frame.gaze_deg.y(), head);
  return to_camera(head, frame.pose);
}

Vec2d SynthRenderer::iris_centre(const SynthFrame& frame, int eye) const {
  return project_iris_centre(eyes_, eye, turned_axis(eyes_, eye, frame.gaze_deg.x(), frame.gaze_deg.y()),
                             painted_iris_depth_[eye], frame.pose, performance_.camera);
}

Positions SynthRenderer::detailed_face(const SynthFrame& frame) const {
  const Positions cam = head_positions(frame);
  const Positions face = cam.leftCols(regions::kFace.num_vertices());
  if (!detail_) return face;
  const Positions coarse_normals = vertex_normals(face, face_triangles_);
  Positions normals = subdivision_.prolong(coarse_normals);
  Positions fine = subdivision_.prolong(face);
  for (int v = 0; v < fine.cols(); ++v) fine.col(v) += displacement_[v] * normals.col(v).normalized();
  return fine;
}

cv::Mat SynthRenderer::render(const SynthFrame& frame, std::mt19937_64& noise_rng) const {
  const SynthOptions& o = performance_.options;
  const Positions head = head_positions(frame);
  // One mesh: the whole head's vertices, then (with detail) the fine face.
  Positions vertices;
  std::vector<Triangle> triangles = head_triangles_;
  Positions albedo;
  if (detail_) {
    const Positions fine = detailed_face(frame);
    vertices.resize(3, head.cols() + fine.cols());
    vertices << head, fine;
    albedo.resize(3, vertices.cols());
    albedo << appearance_.vertex_albedo, fine_albedo_;
    const int offset = static_cast<int>(head.cols());
    for (const Triangle& t : subdivision_.triangles) triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  } else {
    vertices = head;
    albedo = appearance_.vertex_albedo;
    triangles.insert(triangles.end(), face_triangles_.begin(), face_triangles_.end());
  }
  Positions normals = vertex_normals(vertices, triangles);
  // The iris is a flat disc under the cornea, evenly lit across: shaded
  // with the eye's axis, not the cornea's sphere (which, lit from above,
  // darkened the iris's lower half and drew the iris search down).
  const Mat3d model_to_camera = frame.pose.model_to_camera_rotation();
  for (int eye = 0; eye < 2; ++eye) {
    const Vec3f axis =
        (model_to_camera * turned_axis(eyes_, eye, frame.gaze_deg.x(), frame.gaze_deg.y())).cast<float>();
    for (const int v : appearance_.iris_vertices[eye]) normals.col(v) = axis;
  }

  const PinholeCamera cam = performance_.camera.resized(kSupersample);
  RasterBuffers buffers;
  buffers.resize(o.width * kSupersample, o.height * kSupersample);
  rasterize(vertices, triangles, cam, buffers);
  cv::Mat canvas = background_.clone();
  shade_lambertian(buffers, triangles, albedo, normals, frame.lighting, canvas);
  cv::Mat small;
  cv::resize(canvas, small, cv::Size(o.width, o.height), 0, 0, cv::INTER_AREA);
  if (o.noise_sigma > 0) add_sensor_noise(small, o.noise_sigma, noise_rng);
  cv::Mat out;
  small.convertTo(out, CV_8UC3, 255.0);
  return out;
}

Landmarks SynthRenderer::landmarks(const SynthFrame& frame) const {
  const Positions model_face = model_.evaluate(performance_.identity, frame.expression, regions::kFace);
  const Mat3d r = frame.pose.model_to_camera_rotation();
  const auto vertices = landmark_vertices_for_pose(model_, contour_, model_face, r, frame.pose.translation);
  Landmarks lm;
  for (int i = 0; i < kNumLandmarks; ++i) {
    const Vec3d p = r * model_face.col(vertices[i]).cast<double>() + frame.pose.translation;
    lm[i] = performance_.camera.project(p).cast<float>();
  }
  return lm;
}

Landmarks SynthRenderer::landmark_vertex_projections(const SynthFrame& frame) const {
  const Positions model_face = model_.evaluate(performance_.identity, frame.expression, regions::kFace);
  const Mat3d r = frame.pose.model_to_camera_rotation();
  Landmarks lm;
  for (int i = 0; i < kNumLandmarks; ++i) {
    const Vec3d p = r * model_face.col(model_.landmarks.vertices[i]).cast<double>() + frame.pose.translation;
    lm[i] = performance_.camera.project(p).cast<float>();
  }
  return lm;
}

}  // namespace facecap
