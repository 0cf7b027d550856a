#include "facecap/pipeline/uv_passes.hpp"

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/model/face_model.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/frame_files.hpp"
#include "facecap/refine/mesh_hierarchy.hpp"
#include "facecap/render/uv_pass.hpp"

namespace facecap {

namespace fs = std::filesystem;

UvPasses::UvPasses(const FaceModel& model, const fs::path& dir, cv::Size size)
    : dir_(dir / "uv"), size_(size), coarse_(model.region_mesh(regions::kFace)) {
  ensure_writable_dir(dir_);
}

void UvPasses::add(int frame, const Positions& points, const PinholeCamera& camera, const MeshHierarchy* hierarchy) {
  const TriangleMesh* mesh = &coarse_;
  if (hierarchy != nullptr) {
    if (!finest_) finest_ = level_uv_mesh(*hierarchy, hierarchy->num_levels() - 1, per_vertex_uvs(coarse_));
    mesh = &*finest_;
  }
  if (points.cols() != mesh->num_vertices)
    throw Error("a UV pass needs one point per vertex of the face region (or of its finest level)");
  write(frame, uv_pass(*mesh, points, camera, size_, buffers_));
}

void UvPasses::add_empty(int frame) { write(frame, cv::Mat(size_, CV_16UC4, cv::Scalar::all(0))); }

void UvPasses::write(int frame, cv::Mat pass) {
  constexpr size_t kMostWaiting = 2;
  while (pending_.size() >= kMostWaiting) {
    pending_.front().get();  // rethrows the write's error
    pending_.pop_front();
  }
  const std::string name = frame_file_name(frame, "png");
  pending_.push_back(writer_.submit([file = dir_ / name, image = std::move(pass)] { write_image(file, image); }));
  written_.insert(name);
}

void UvPasses::finish() {
  for (; !pending_.empty(); pending_.pop_front()) pending_.front().get();
  remove_unwritten_frame_files(dir_, {"png"}, written_);
}

}  // namespace facecap
