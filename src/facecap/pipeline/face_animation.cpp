#include "facecap/pipeline/face_animation.hpp"

#include <cmath>
#include <map>
#include <utility>

#include "facecap/core/error.hpp"
#include "facecap/model/regions.hpp"

namespace facecap {

namespace {

constexpr float kMetresPerCentimetre = 0.01f;

// glTF vertices: one per distinct (model vertex, UV) pair of the face
// region's triangles, so that a UV seam gets a vertex on each side.
struct SplitMesh {
  std::vector<int> source;  // model vertex (region-local) per glTF vertex
  std::vector<int> uv;      // UV index per glTF vertex (-1: none)
  std::vector<Triangle> triangles;
};

SplitMesh split_at_uv_seams(const TriangleMesh& mesh) {
  SplitMesh out;
  std::map<std::pair<int, int>, int> index;
  const bool has_uv = !mesh.triangle_uvs.empty();
  out.triangles.reserve(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      const int uv = has_uv ? mesh.triangle_uvs[t][k] : -1;
      const auto [it, added] = index.try_emplace({v, uv}, int(out.source.size()));
      if (added) {
        out.source.push_back(v);
        out.uv.push_back(uv);
      }
      tri[k] = it->second;
    }
    out.triangles.push_back(tri);
  }
  return out;
}

// Region-local 3 x N columns gathered into glTF vertex order, in metres.
Positions gather_metres(const Positions& region, const std::vector<int>& source) {
  Positions out(3, source.size());
  for (size_t i = 0; i < source.size(); ++i) out.col(i) = region.col(source[i]) * kMetresPerCentimetre;
  return out;
}

}  // namespace

std::vector<int> face_animation_source_vertices(const FaceModel& model) {
  return split_at_uv_seams(model.region_mesh(regions::kFace)).source;
}

GltfAnimatedMesh face_animation(const FaceModel& model, const Eigen::VectorXd& identity,
                                const std::vector<FaceAnimationKey>& keys, const FaceAnimationCamera& camera) {
  const Region& face = regions::kFace;
  const TriangleMesh mesh = model.region_mesh(face);
  const SplitMesh split = split_at_uv_seams(mesh);
  const int n = face.num_vertices();

  GltfAnimatedMesh out;
  out.name = "face";
  const Eigen::VectorXf shape = model.identity_shape(identity.cast<float>(), face);
  const Eigen::Map<const Positions> rest(shape.data(), 3, n);
  out.positions = gather_metres(rest, split.source);
  // Normals from the unsplit mesh, so that both sides of a seam agree.
  const Positions normals = vertex_normals(rest, mesh.triangles);
  out.normals.resize(3, Eigen::Index(split.source.size()));
  for (size_t i = 0; i < split.source.size(); ++i) out.normals.col(i) = normals.col(split.source[i]);
  if (!mesh.triangle_uvs.empty()) {
    out.uvs.resize(2, Eigen::Index(split.uv.size()));
    for (size_t i = 0; i < split.uv.size(); ++i) {
      const Vec2f& t = mesh.uvs[split.uv[i]];
      out.uvs.col(i) = Eigen::Vector2f(t.x(), 1.0f - t.y());  // glTF's v runs down the image
    }
  }
  out.triangles = split.triangles;
  const Eigen::Index row0 = 3 * face.first_vertex;
  for (int j = 0; j < model.num_expressions(); ++j) {
    const Eigen::VectorXf delta = model.expression_basis.block(row0, j, 3 * n, 1);
    out.morph_targets.push_back(gather_metres(Eigen::Map<const Positions>(delta.data(), 3, n), split.source));
    out.morph_target_names.push_back(model.expression_names[j]);
  }

  // Keys: the node's transform is F R F and F t (the header's axes).
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();
  out.weights = Eigen::MatrixXf::Zero(model.num_expressions(), Eigen::Index(keys.size()));
  for (size_t k = 0; k < keys.size(); ++k) {
    const FaceAnimationKey& key = keys[k];
    if (key.expression.size() > model.num_expressions())
      throw Error("an animation key has more expression weights than the model");
    out.times.push_back(float(key.time));
    out.translations.push_back((flip * key.pose.translation).cast<float>() * kMetresPerCentimetre);
    Eigen::Quaternionf q(Eigen::Matrix3f((flip * key.pose.rotation_matrix() * flip).cast<float>()));
    q.normalize();
    // The shorter way round from the previous key, so that players
    // interpolating linearly do not spin the head.
    if (k > 0 && q.coeffs().dot(out.rotations.back().coeffs()) < 0) q.coeffs() *= -1.0f;
    out.rotations.push_back(q);
    out.weights.col(Eigen::Index(k)).head(key.expression.size()) = key.expression;
  }
  if (camera.focal_px > 0 && camera.width > 0 && camera.height > 0) {
    GltfCamera c;
    c.yfov_rad = 2.0 * std::atan(0.5 * camera.height / camera.focal_px);
    c.aspect_ratio = double(camera.width) / camera.height;
    out.camera = c;
  }
  out.asset_extras = {{"model", "ICT Face Model Light (ICT-FaceKit, MIT): face region, the video's identity"},
                      {"morph_targets", "the 53 ICT expression blend shapes under their ARKit names"},
                      {"units", "metres"},
                      {"camera", "the fitted pinhole camera at the origin, principal point at the image centre"}};
  return out;
}

}  // namespace facecap
