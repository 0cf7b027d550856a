#include "facecap/pipeline/face_animation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "facecap/core/error.hpp"
#include "facecap/core/view_frame.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/eyeballs.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_matte.hpp"

namespace facecap {

namespace {

constexpr float kMetresPerCentimetre = 0.01f;

// One part's glTF vertices: `source` holds the model vertex (whole-head
// index) of each, `uv` its UV index (-1: none); its triangles in glTF
// vertices, and the same in model vertices (unsplit).
struct Part {
  std::vector<int> source;
  std::vector<int> uv;
  std::vector<Triangle> triangles;
  std::vector<Triangle> model_triangles;
};

// One glTF vertex per distinct (model vertex, UV) pair of the triangles, so
// that a UV seam gets a vertex on each side. `first_vertex` offsets the
// mesh's (region-local) indices to the model's.
Part split_at_uv_seams(const TriangleMesh& mesh, int first_vertex, bool keep_uvs) {
  Part out;
  std::map<std::pair<int, int>, int> index;
  const bool has_uv = keep_uvs && !mesh.triangle_uvs.empty();
  out.triangles.reserve(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    Triangle tri, model_tri;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k] + first_vertex;
      model_tri[k] = v;
      const int uv = has_uv ? mesh.triangle_uvs[t][k] : -1;
      const auto [it, added] = index.try_emplace({v, uv}, int(out.source.size()));
      if (added) {
        out.source.push_back(v);
        out.uv.push_back(uv);
      }
      tri[k] = it->second;
    }
    out.triangles.push_back(tri);
    out.model_triangles.push_back(model_tri);
  }
  return out;
}

Part face_part(const FaceModel& model) {
  return split_at_uv_seams(model.region_mesh(regions::kFace), regions::kFace.first_vertex, true);
}

// What shows through the face's eye and mouth holes: the mouth socket, gums,
// tongue, teeth, eye sockets and eyeballs, with the polygons that join them
// to the face; not the back of the head, nor the eyes' transparent layers.
Part interior_part(const FaceModel& model) {
  auto inside = [](int v) {
    return v <= regions::kEyeballRight.last_vertex &&
           (v < regions::kHeadAndNeck.first_vertex || v > regions::kHeadAndNeck.last_vertex);
  };
  std::vector<Polygon> chosen;
  for (const Polygon& p : model.polygons) {
    bool keep = true, all_face = true;
    for (int k = 0; k < p.size(); ++k) {
      keep = keep && inside(p.v[k]);
      all_face = all_face && p.v[k] <= regions::kFace.last_vertex;
    }
    if (keep && !all_face) chosen.push_back(p);
  }
  return split_at_uv_seams(triangulate(chosen, model.uvs, model.num_vertices), 0, false);
}

// Linear RGB of the interior by region: teeth pale, the rest of the mouth
// pink to dark, where it joins the face a skin tone; the eyeballs white
// with a dark brown iris (kIrisRadiusCm) and a black pupil (2 mm) round
// each eye's axis at rest, so that the eyes show where they look.
Eigen::Vector3f interior_colour(int v, const EyeballGeometry& eyes, const Positions& head) {
  if (v <= regions::kFace.last_vertex) return {0.55f, 0.38f, 0.32f};
  if (v <= regions::kMouthSocket.last_vertex) return {0.30f, 0.08f, 0.08f};
  if (v <= regions::kEyeSocketRight.last_vertex) return {0.25f, 0.12f, 0.12f};
  if (v <= regions::kGumsAndTongue.last_vertex) return {0.60f, 0.22f, 0.22f};
  if (v <= regions::kTeeth.last_vertex) return {0.85f, 0.82f, 0.72f};
  const Vec3d p = head.col(v).cast<double>();
  const int eye = (p - eyes.centre[0]).norm() <= (p - eyes.centre[1]).norm() ? 0 : 1;
  // How far the vertex lies from the eye's axis (cm), on the front half.
  const Vec3d from_centre = (p - eyes.centre[eye]).normalized();
  const double off_axis = from_centre.cross(eyes.rest_axis[eye]).norm() * eyes.radius[eye];
  const bool front = from_centre.dot(eyes.rest_axis[eye]) > 0;
  constexpr double kPupilRadiusCm = 0.2;
  if (front && off_axis < kPupilRadiusCm) return {0.02f, 0.02f, 0.02f};
  if (front && off_axis < kIrisRadiusCm) return {0.10f, 0.05f, 0.025f};
  return {0.85f, 0.85f, 0.82f};
}

// Whole-head 3N values gathered into a part's vertex order, in metres.
Positions gather_metres(const Eigen::VectorXf& head, const std::vector<int>& source) {
  Positions out(3, source.size());
  for (size_t i = 0; i < source.size(); ++i) out.col(i) = head.segment<3>(3 * source[i]) * kMetresPerCentimetre;
  return out;
}

// Whole-head offsets (3N, cm) that turn both eyeballs of the rest shape by
// kEyeTurnTargetDeg toward each of kEyeTurnTargetNames.
std::vector<Eigen::VectorXf> eye_turn_targets(const FaceModel& model, const FaceAnimationRest& rest) {
  const Eigen::Map<const Positions> head(rest.head.data(), 3, model.num_vertices);
  const EyeballGeometry eyes = head_eyeball_geometry(model, Positions(head));
  const double a = kEyeTurnTargetDeg;
  std::vector<Eigen::VectorXf> out;
  for (const auto& [yaw, pitch] : {std::pair{a, 0.0}, {-a, 0.0}, {0.0, a}, {0.0, -a}}) {
    Positions turned = head;
    turn_eyeballs(eyes, yaw, pitch, turned);
    turned -= head;
    out.emplace_back(Eigen::Map<const Eigen::VectorXf>(turned.data(), turned.size()));
  }
  return out;
}

// The eye-turn weights of a head-relative gaze.
Eigen::Vector4f eye_turn_weights(const Vec2d& gaze_deg) {
  const double yaw = gaze_deg.x() / kEyeTurnTargetDeg, pitch = gaze_deg.y() / kEyeTurnTargetDeg;
  return Eigen::Vector4d(std::max(0.0, yaw), std::max(0.0, -yaw), std::max(0.0, pitch), std::max(0.0, -pitch))
      .cast<float>();
}

// Normals from the unsplit triangles, so that both sides of a UV seam agree.
GltfPrimitive make_primitive(const FaceModel& model, const FaceAnimationRest& rest, const Part& part,
                             const std::vector<Eigen::VectorXf>& eye_turns) {
  GltfPrimitive p;
  p.positions = gather_metres(rest.head, part.source);
  const Positions normals =
      vertex_normals(Eigen::Map<const Positions>(rest.head.data(), 3, model.num_vertices), part.model_triangles);
  p.normals.resize(3, Eigen::Index(part.source.size()));
  for (size_t i = 0; i < part.source.size(); ++i) p.normals.col(i) = normals.col(part.source[i]);
  p.triangles = part.triangles;
  for (int j = 0; j < model.num_expressions(); ++j)
    p.morph_targets.push_back(gather_metres(model.expression_basis.col(j), part.source) * rest.blend_shape_scale);
  for (const Eigen::VectorXf& turn : eye_turns) p.morph_targets.push_back(gather_metres(turn, part.source));
  return p;
}

}  // namespace

void append_animation_key(std::vector<FaceAnimationKey>& keys, bool timeline, int index, double time,
                          const HeadPose& pose, const Eigen::VectorXf& expression, std::optional<Vec2d> gaze_deg) {
  const double t = timeline ? time : index / 30.0;
  if (!keys.empty() && t <= keys.back().time) return;
  keys.push_back({t, pose, expression, gaze_deg});
}

std::optional<Vec2d> key_gaze(const GazeEstimate& gaze) {
  if (!gaze.valid()) return std::nullopt;
  return gaze.angles_deg();
}

std::vector<std::vector<int>> face_animation_source_vertices(const FaceModel& model) {
  return {face_part(model).source, interior_part(model).source};
}

FaceAnimationRest identity_rest(const FaceModel& model, const Eigen::VectorXf& identity) {
  const Region all{"all", 0, model.num_vertices - 1, 0, int(model.polygons.size()) - 1};
  return {model.identity_shape(identity, all), 1.0f};
}

GltfAnimatedMesh face_animation(const FaceModel& model, const Eigen::VectorXd& identity,
                                const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera) {
  return face_animation(model, identity_rest(model, identity.cast<float>()), keys, camera);
}

GltfAnimatedMesh face_animation(const FaceModel& model, const FaceAnimationRest& rest,
                                const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera) {
  if (rest.head.size() != 3 * Eigen::Index(model.num_vertices))
    throw Error("the animation's rest shape does not have the model's vertex count");
  if (!rest.head.allFinite() || !std::isfinite(rest.blend_shape_scale))
    throw Error("the animation's rest shape is not finite");
  GltfAnimatedMesh out;
  out.name = "face";

  const std::vector<Eigen::VectorXf> eye_turns = eye_turn_targets(model, rest);
  const Part face = face_part(model);
  GltfPrimitive skin = make_primitive(model, rest, face, eye_turns);
  skin.name = "face";
  skin.uvs.resize(2, Eigen::Index(face.uv.size()));
  for (size_t i = 0; i < face.uv.size(); ++i) {
    const Vec2f& t = model.uvs[face.uv[i]];
    skin.uvs.col(i) = Eigen::Vector2f(t.x(), 1.0f - t.y());  // glTF's v runs down the image
  }
  out.primitives.push_back(std::move(skin));

  const Part inner = interior_part(model);
  GltfPrimitive mouth_and_eyes = make_primitive(model, rest, inner, eye_turns);
  mouth_and_eyes.name = "mouth and eyes";
  mouth_and_eyes.base_colour = Eigen::Vector3f::Ones();
  mouth_and_eyes.colours.resize(3, Eigen::Index(inner.source.size()));
  {
    const Positions head = Eigen::Map<const Positions>(rest.head.data(), 3, model.num_vertices);
    const EyeballGeometry eyes = head_eyeball_geometry(model, head);
    for (size_t i = 0; i < inner.source.size(); ++i)
      mouth_and_eyes.colours.col(i) = interior_colour(inner.source[i], eyes, head);
  }
  out.primitives.push_back(std::move(mouth_and_eyes));
  out.morph_target_names = model.expression_names;
  out.morph_target_names.insert(out.morph_target_names.end(), kEyeTurnTargetNames.begin(), kEyeTurnTargetNames.end());

  // Keys: the node's transform is the pose in the view frame (the header's axes).
  const int ne = model.num_expressions();
  out.weights = Eigen::MatrixXf::Zero(ne + 4, Eigen::Index(keys.size()));
  Eigen::Vector4f eye_turn = Eigen::Vector4f::Zero();  // held through keys with no gaze (blinks)
  for (size_t k = 0; k < keys.size(); ++k) {
    const FaceAnimationKey& key = keys[k];
    if (key.expression.size() > model.num_expressions())
      throw Error("an animation key has more expression weights than the model");
    out.times.push_back(float(key.time));
    const ViewPose view = pose_in_view_frame(key.pose);
    out.translations.push_back(view.translation.cast<float>() * kMetresPerCentimetre);
    Eigen::Quaternionf q(Eigen::Matrix3f(view.rotation.cast<float>()));
    q.normalize();
    // The shorter way round from the previous key, so that players
    // interpolating linearly do not spin the head.
    if (k > 0 && q.coeffs().dot(out.rotations.back().coeffs()) < 0) q.coeffs() *= -1.0f;
    out.rotations.push_back(q);
    out.weights.col(Eigen::Index(k)).head(key.expression.size()) = key.expression;
    if (key.gaze_deg) eye_turn = eye_turn_weights(*key.gaze_deg);
    out.weights.col(Eigen::Index(k)).tail<4>() = eye_turn;
  }
  if (camera.focal_px > 0 && camera.width > 0 && camera.height > 0) {
    GltfCamera c;
    c.yfov_rad = 2.0 * std::atan(0.5 * camera.height / camera.focal_px);
    c.aspect_ratio = double(camera.width) / camera.height;
    out.camera = c;
  }
  out.asset_extras = {
      {"model", "ICT Face Model Light (ICT-FaceKit, MIT): face region, mouth and eyes, the video's identity"},
      {"morph_targets",
       "the 53 ICT expression blend shapes under their ARKit names, then eyesTurnLeft/Right/Up/Down: both eyeballs "
       "turned 30 degrees (the subject's left, right, up, down), weighted by the measured gaze angle / 30"},
      {"units", "metres"},
      {"camera", "the fitted pinhole camera at the origin, principal point at the image centre"},
      {"face_matte",
       "the image named face_matte, used by no material: where a render over the footage shows the face part, in its "
       "UV layout (255: the narrow face, feathered at its outer edge; 0: scalp, ears and neck, the footage's own)"}};
  out.images.push_back({std::string(kFaceMatteImageName), encode_png(face_matte_image(model))});
  return out;
}

}  // namespace facecap
