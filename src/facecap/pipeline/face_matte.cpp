#include "facecap/pipeline/face_matte.hpp"

#include <algorithm>
#include <vector>

#include "facecap/core/edge_distance.hpp"
#include "facecap/core/error.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/render/uv_bake.hpp"

namespace facecap {

namespace {

// narrow_face_matte on `mesh`, the model's face region.
Eigen::VectorXf matte_on(const FaceModel& model, const TriangleMesh& mesh, float feather_mm) {
  if (!(feather_mm > 0)) throw Error("the face matte's feather must be positive");
  const Eigen::VectorXf mean_face = model.identity_shape(Eigen::VectorXf(), regions::kFace);
  const Positions mm = 10.0f * Eigen::Map<const Positions>(mean_face.data(), 3, mesh.num_vertices);
  // The face region's vertices are the model's first; the narrow face's are
  // the first of those.
  const int narrow = regions::kNarrowFace.num_vertices();
  std::vector<int> off_the_face(size_t(mesh.num_vertices - narrow));
  for (size_t i = 0; i < off_the_face.size(); ++i) off_the_face[i] = narrow + int(i);
  const std::vector<double> distance =
      edge_path_distances(mm, vertex_adjacency(mesh.triangles, mesh.num_vertices), off_the_face);
  Eigen::VectorXf matte = Eigen::VectorXf::Zero(mesh.num_vertices);
  for (int v = 0; v < narrow; ++v) matte[v] = smoothstep(0.0f, feather_mm, float(distance[size_t(v)]));
  return matte;
}

}  // namespace

Eigen::VectorXf narrow_face_matte(const FaceModel& model, float feather_mm) {
  return matte_on(model, model.region_mesh(regions::kFace), feather_mm);
}

cv::Mat face_matte_image(const FaceModel& model, int size, float feather_mm) {
  const TriangleMesh mesh = model.region_mesh(regions::kFace);
  const cv::Mat matte =
      UvBaker(mesh.triangles, rasterize_uv(mesh, size)).bake(matte_on(model, mesh, feather_mm).transpose());
  cv::Mat grey;
  matte.convertTo(grey, CV_8U, 255.0);
  return grey;
}

}  // namespace facecap
