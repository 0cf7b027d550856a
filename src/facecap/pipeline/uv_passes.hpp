#pragma once
// `track --uv-pass`: each frame's UV pass (render/uv_pass.hpp) at the
// input's size, DIR/uv/frame_NNNNNN.png (16-bit RGBA: red u, green v of the
// ICT UV layout, alpha the face region's coverage): a compositor's ST map
// that puts a texture painted in that layout (albedo.png, texture.png) onto
// the face in every frame. A frame without a face has an empty pass, so that
// the sequence has no gaps.
#include <deque>
#include <filesystem>
#include <future>
#include <optional>
#include <string>
#include <unordered_set>

#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/serial_worker.hpp"
#include "facecap/render/rasterizer.hpp"

namespace facecap {

struct FaceModel;
class MeshHierarchy;

class UvPasses {
 public:
  // Passes of `size` into DIR/uv, which it makes (throws facecap::Error when it cannot).
  UvPasses(const FaceModel& model, const std::filesystem::path& dir, cv::Size size);

  // Frame `frame`'s pass: the face region at `points` (camera space, cm)
  // through `camera`; `points` are the coarse face region's, or, with
  // `hierarchy`, its finest level's (the refined surface).
  void add(int frame, const Positions& points, const PinholeCamera& camera, const MeshHierarchy* hierarchy = nullptr);
  // An empty pass for a frame without a face.
  void add_empty(int frame);

  // Waits for the passes still being written (throws facecap::Error where
  // one could not be) and removes the passes in DIR/uv of an earlier run
  // that this one did not write.
  void finish();

  int passes_written() const { return int(written_.size()); }

 private:
  // Encodes and writes the pass on the writer's thread, beside the next
  // frames' capture, with at most two passes waiting.
  void write(int frame, cv::Mat pass);

  std::filesystem::path dir_;
  cv::Size size_;
  TriangleMesh coarse_;                 // the face region, per-corner UVs
  std::optional<TriangleMesh> finest_;  // its finest level, made at the first refined frame
  RasterBuffers buffers_;
  std::unordered_set<std::string> written_;
  std::deque<std::future<void>> pending_;
  SerialWorker writer_{"facecap-uv"};  // last: destroyed first, so a write in flight ends before what it uses
};

}  // namespace facecap
