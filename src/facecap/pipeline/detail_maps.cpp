#include "facecap/pipeline/detail_maps.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/version.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/frame_files.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/render/uv_bake.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

constexpr const char* kDetailFolder = "detail";
constexpr const char* kDetailInfo = "detail.json";

}  // namespace

uint16_t DetailEncoding::encode(double d_mm) const {
  return uint16_t(std::clamp(std::round(d_mm * scale() + kOffset), 0.0, 65535.0));
}

double DetailEncoding::decode(uint16_t v) const { return (v - kOffset) / scale(); }

DetailMaps::DetailMaps(const FaceModel& model, const fs::path& dir, int size, DetailEncoding encoding)
    : dir_(dir / kDetailFolder),
      size_(size),
      encoding_(encoding),
      coarse_uvs_(per_vertex_uvs(model.region_mesh(regions::kFace))) {
  ensure_writable_dir(dir_);
}

void DetailMaps::add(int frame, const MeshHierarchy& hierarchy, const Eigen::VectorXf& displacement_cm) {
  const int finest_level = hierarchy.num_levels() - 1;
  if (finest_level < 0 || displacement_cm.size() != hierarchy.vertices(finest_level))
    throw Error("a detail map needs one displacement per vertex of the hierarchy's finest level");
  if (!baker_) {
    const TriangleMesh finest = level_uv_mesh(hierarchy, finest_level, coarse_uvs_);
    baker_.emplace(finest.triangles, rasterize_uv(finest, size_));
  }
  // The displacement in millimetres (the refinement's is in centimetres).
  const Eigen::VectorXf d_mm = 10.0f * displacement_cm;
  vertices_ += d_mm.size();
  clamped_ += (d_mm.array().abs() > float(encoding_.range_mm)).count();
  min_mm_ = std::min(min_mm_, double(d_mm.minCoeff()));
  max_mm_ = std::max(max_mm_, double(d_mm.maxCoeff()));
  sum_squares_ += d_mm.squaredNorm();
  // DetailEncoding::encode, texel by texel (rounded and saturated).
  cv::Mat map;
  baker_->bake(d_mm.transpose()).convertTo(map, CV_16UC1, encoding_.scale(), DetailEncoding::kOffset);
  write_map(frame, map);
}

void DetailMaps::add_flat(int frame) {
  write_map(frame, cv::Mat(size_, size_, CV_16UC1, cv::Scalar(DetailEncoding::kOffset)));
  ++flat_maps_;
}

void DetailMaps::write_map(int frame, const cv::Mat& map) {
  const std::string name = frame_file_name(frame, "png");
  write_image(dir_ / name, map);
  written_.insert(name);
}

void DetailMaps::finish() {
  remove_unwritten_frame_files(dir_, {"png"}, written_);
  const double strength_cm = 2 * encoding_.range_mm / 10;
  nlohmann::json j;
  j["format"] = "facecap-detail-maps";
  j["version"] = 1;
  j["generator"] = "facecap " + std::string(kFacecapVersion);
  j["maps"] = maps_written();
  j["flat_maps"] = flat_maps_;
  j["files"] =
      "frame_NNNNNN.png, NNNNNN the frame's number in the input, one for every frame: a flat one (0 mm "
      "everywhere) where the frame has no refined face";
  j["size"] = {size_, size_};
  j["uv_layout"] = "ICT-FaceKit's (albedo.png, texture.png and the meshes' UVs; v up, as in OBJ)";
  j["meaning"] =
      "the refinement's displacement along the tracked surface's outward normal (eq. 4.11 of the "
      "dissertation, M_d = M + d N), millimetres, positive outward";
  j["encoding"] = {{"bits", 16},
                   {"colour_space", "non-colour data (linear)"},
                   {"range_mm", encoding_.range_mm},
                   {"displacement_mm", "(value / 65535 - 0.5) * 2 * range_mm"},
                   {"clamped_fraction", clamped_fraction()}};
  j["blender_displace"] = {{"texture_coordinates", "UV"},
                           {"midlevel", 0.5},
                           {"strength_cm", strength_cm},
                           {"note", "the meshes are in centimetres: strength in their units is 2 * range_mm / 10"}};
  // Over the finest level's vertices in every map; none without a map.
  j["displacement_mm"] = nullptr;
  if (vertices_ > 0)
    j["displacement_mm"] = {{"min", min_mm_}, {"max", max_mm_}, {"rms", std::sqrt(sum_squares_ / double(vertices_))}};
  write_text_file(dir_ / kDetailInfo, j.dump(2) + "\n");
}

}  // namespace facecap
