#pragma once
// What covers a tracked face through a shot, found as the swap finds it
// (occlusion_mask.hpp's colour test against the shot's first frames with
// final lighting, moving_cover.hpp's motion test), for an edit that
// re-renders the face from the frame itself: an expression transformation
// would otherwise move a hand over the mouth with the lips.
#include <memory>
#include <opencv2/core.hpp>

#include "facecap/model/face_model.hpp"
#include "facecap/swap/frame_preparation.hpp"
#include "facecap/swap/occlusion_mask.hpp"

namespace facecap {

// Whether an edit keeps what covers the face in front of it, and whether it
// also looks for covers by their motion (a hand of the skin's own colour).
struct CoverOptions {
  bool keep_occluders = true;
  bool moving_covers = true;
  int reference_frames = 5;  // frames of a shot, from the first with final lighting, that show the face uncovered
};

// Millimetres on the mean face per unit of `skin`'s UV: a grid's scale
// that needs no one's identity (about a millimetre a texel).
double mean_face_mm_per_uv(const FaceModel& model, const TriangleMesh& skin);

class FaceCovers {
 public:
  // On `skin` (skin_texture.hpp's skin_mesh, which must outlive this) with
  // a grid at `mm_per_uv`: a swap's is the source face's, which its
  // expression ratio shares; a transform's, mean_face_mm_per_uv.
  FaceCovers(const FaceModel& model, const TriangleMesh& skin, CoverOptions options, double mm_per_uv);

  // Each frame's unshading and motion, for any thread, frames in order
  // (FramePreparation::prepare, with the face region's camera-space points).
  std::unique_ptr<FramePreparation> new_preparation() const;

  // How covered each texel of the skin is in this frame (OcclusionMask::
  // covered), frames in order; the first CoverOptions::reference_frames of
  // a shot are its references. `lighting_final`: false while the frame's
  // lighting is provisional (Refinement::albedo_final), whose unshading is
  // then no reference for the frames that follow.
  cv::Mat covered(const PreparedFrame& prepared, bool lighting_final);

  // A shot cut: the next frames are references again.
  void restart();

  const TriangleMesh& skin() const { return *skin_; }
  const MillimetreGrid& grid() const { return occlusion_.grid(); }

 private:
  const FaceModel* model_;
  CoverOptions options_;
  const TriangleMesh* skin_;
  OcclusionMask occlusion_;
  int references_ = 0;
};

}  // namespace facecap
