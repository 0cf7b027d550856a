#include "facecap/swap/skin_texture.hpp"

#include "facecap/compose/face_reshading.hpp"
#include "facecap/model/regions.hpp"

namespace facecap {

TriangleMesh skin_mesh(const FaceModel& model) {
  const TriangleMesh face = model.region_mesh(regions::kFace);
  TriangleMesh skin;
  skin.uvs = face.uvs;
  skin.num_vertices = face.num_vertices;
  for (size_t t = 0; t < face.triangles.size(); ++t) {
    const Triangle& tri = face.triangles[t];
    if (tri[0] > regions::kNarrowFace.last_vertex || tri[1] > regions::kNarrowFace.last_vertex ||
        tri[2] > regions::kNarrowFace.last_vertex)
      continue;
    skin.triangles.push_back(tri);
    skin.triangle_uvs.push_back(face.triangle_uvs[t]);
  }
  return skin;
}

std::vector<std::vector<cv::Point>> feature_holes(const FaceModel& model, const Positions& points,
                                                  const PinholeCamera& camera) {
  std::vector<std::vector<cv::Point>> holes;
  for (const auto& [first, last] : {std::pair{36, 41}, std::pair{42, 47}, std::pair{60, 67}}) {
    std::vector<int> vertices(model.landmarks.vertices.begin() + first, model.landmarks.vertices.begin() + last + 1);
    std::vector<cv::Point> polygon;
    for (const cv::Point2f& q : project_vertices(points, vertices, camera))
      polygon.emplace_back(cvRound(q.x), cvRound(q.y));
    holes.push_back(std::move(polygon));
  }
  return holes;
}

FaceTexture unshade_photo(const FaceModel& model, const cv::Mat& photo, const Positions& camera_points,
                          const PinholeCamera& camera, const ShCoeffs& lighting, const TriangleMesh& skin,
                          const UvTexelMap& map, double mirror_low_pass_texels) {
  FaceTexture t = unshade_face(photo, camera_points, skin.triangles, camera, lighting, map,
                               feature_holes(model, camera_points, camera));
  drop_non_skin(t);
  if (mirror_low_pass_texels > 0) complete_from_mirror(t, mirror_low_pass_texels);
  return t;
}

}  // namespace facecap
