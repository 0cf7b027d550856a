#pragma once
// `track --refine --detail-maps`: each refined frame's detail, the
// displacement the refinement adds along the tracked surface's normals (d of
// M_d = M + d N, eq. 4.11, on the hierarchy's finest level), baked into the
// ICT UV layout (that of albedo.png, texture.png and the meshes' UVs) as a
// 16-bit grey PNG a frame, DIR/detail/frame_NNNNNN.png, with
// DIR/detail/detail.json saying how to read them back: a video's
// displacement maps, as DECA gives one for a photo, for a subdivided mesh's
// Displace modifier in Blender or a material's displacement elsewhere.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "facecap/core/mesh.hpp"
#include "facecap/render/uv_bake.hpp"

namespace facecap {

struct FaceModel;
class MeshHierarchy;

// A displacement d (mm) as a 16-bit value v: v / 65535 = 0.5 + d / (2 range),
// so that a displacement with midlevel 0.5 and strength 2 range (Blender's
// Displace modifier, its texture read as non-colour data) gives d back to
// 2 range / 65535 (0.06 micrometres at the default range); a displacement
// beyond +-range is clamped to it.
struct DetailEncoding {
  double range_mm = 2.0;
  static constexpr double kOffset = 65535.0 * 0.5;           // the value of d = 0
  double scale() const { return 65535.0 / (2 * range_mm); }  // values per millimetre
  uint16_t encode(double d_mm) const;
  double decode(uint16_t v) const;
};

class DetailMaps {
 public:
  // Maps of size x size texels into DIR/detail, which it makes (throws
  // facecap::Error when it cannot).
  DetailMaps(const FaceModel& model, const std::filesystem::path& dir, int size, DetailEncoding encoding = {});

  // Writes frame `frame`'s map: `displacement_cm` per vertex of the finest
  // level of `hierarchy` (Refinement::displacement; the refiner's hierarchy,
  // fixed at its first frame, the same for every map).
  void add(int frame, const MeshHierarchy& hierarchy, const Eigen::VectorXf& displacement_cm);

  // Writes frame `frame`'s map as flat (0 mm everywhere): a frame without a
  // refined face, so that the maps make an unbroken image sequence, as
  // Blender's and compositors' image sequences need.
  void add_flat(int frame);

  // Writes detail.json and removes the frame maps in DIR/detail of an earlier
  // run that this one did not write (its frames past this run's end, or lost
  // in it, would read as part of this sequence).
  void finish();

  // Maps written, flat ones included; flat ones alone.
  int maps_written() const { return int(written_.size()); }
  int flat_maps_written() const { return flat_maps_; }
  // Share of the maps' vertex values (the finest level's) beyond the range,
  // clamped in the maps.
  double clamped_fraction() const { return vertices_ > 0 ? double(clamped_) / double(vertices_) : 0.0; }

 private:
  void write_map(int frame, const cv::Mat& map);

  std::filesystem::path dir_;
  int size_;
  DetailEncoding encoding_;
  std::vector<Vec2f> coarse_uvs_;  // the face region's, one per vertex
  std::optional<UvBaker> baker_;   // the finest level's, made at the first frame
  std::unordered_set<std::string> written_;
  long long vertices_ = 0, clamped_ = 0;
  double min_mm_ = std::numeric_limits<double>::infinity(), max_mm_ = -std::numeric_limits<double>::infinity();
  double sum_squares_ = 0;
  int flat_maps_ = 0;
};

}  // namespace facecap
