#pragma once
// What covers the target's face in a frame (a microphone, a cup, a strand
// of hair, a gloved hand), so that the swap leaves it in front of the new face
// rather than painting over it: a departure from the paper, whose swap
// (§6.3) blends the new face over whatever hides the old one.
//
// Each frame the target face is unshaded into a UV grid about a millimetre
// per texel. A texel is covered where this frame's colour there lies
// outside what the appearance frames showed around it: in some channel, its
// log colour (after the frame's overall shift, which the light's colour
// and level leave, is taken out) is more than min_log_change below the
// least or above the most that any appearance frame saw within slide_mm of
// the texel. The neighbourhood is what tolerates the tracking sliding an
// edge (a brow, a lip, a mole) across the surface; a cover's colour is
// nowhere near. Specks narrower than min_extent_mm are dropped; gaps as
// wide as an edge's band and what the covers enclose are filled, and so is
// what the frame does not see up to unseen_mm from a cover (the new face's
// outline is not the target's); the rest grows by margin_mm and fades over
// feather_mm, so the cover's edge takes the frame's own pixels.
//
// Something that covers the face in its appearance frames is taken for the
// face; a cover of the skin's own colour and brightness (a hand in the same
// light) is not found.
#include <opencv2/core.hpp>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/face_texture.hpp"

namespace facecap {

// MovingCover's evidence (0..1) above which a texel is covered; the mover
// carries only evidence that reaches it (less counts for nothing).
constexpr float kCoveringEvidence = 0.5f;

struct OcclusionOptions {
  float texel_mm = 1.0f;        // the grid, as the expression ratio's
  float min_log_change = 0.7f;  // a factor of 2 in a channel, past what the appearance frames showed nearby
  float slide_mm = 4.0f;        // how far the tracking slides the face's features
  float min_extent_mm = 6.0f;   // narrower covers are noise
  float unseen_mm = 10.0f;      // covers reach this far into what the frame does not see
  float margin_mm = 2.0f;       // the mask grows this far past what was found
  float feather_mm = 2.0f;      // and fades over this width
};

// A covered() grid's value at a UV point (bilinear).
float cover_at(const cv::Mat& cover, const Vec2f& uv);

// A covered() grid drawn into a window of `size` that `camera` sees: at
// each pixel where the skin mesh (`points`, its vertices in camera space)
// shows, the grid's value at its UV (CV_32F; 0 elsewhere).
cv::Mat cover_in_image(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size size,
                       const cv::Mat& cover);

// What an edit leaves in front of the face in such a window: cover_in_image,
// closed across the skin mesh's openings (the mouth, the eyes) where a
// cover lies on both sides of them, up to `across_px` pixels each way.
cv::Mat cover_in_front(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size size,
                       const cv::Mat& cover, int across_px);

class OcclusionMask {
 public:
  // `skin`: the face's triangles with UVs; `mm_per_uv`: millimetres on the
  // face per unit of UV (millimetres_per_uv()).
  OcclusionMask(const TriangleMesh& skin, double mm_per_uv, OcclusionOptions options = {});

  // The appearance frames, each unshaded onto grid() as the camera saw it,
  // nothing dropped as non-skin (FramePreparation's): what the face looks
  // like uncovered.
  void clear_reference();
  void add_reference(const FaceTexture& seen);

  // How covered each texel is (CV_32F, 0..1, grid_size() square over UV
  // [0, 1]^2, row 0 at v = 1) in a frame unshaded so; all zero
  // before any reference. `moving`: MovingCover's evidence on the grid,
  // covered where above kCoveringEvidence whatever its colour (empty: none).
  cv::Mat covered(const FaceTexture& seen, const cv::Mat& moving = {}) const;

  int grid_size() const { return grid_.map.size; }
  const MillimetreGrid& grid() const { return grid_; }

 private:
  OcclusionOptions options_;
  MillimetreGrid grid_;  // about options_.texel_mm per texel
  // Over the appearance frames so far, per texel and channel, the least and
  // the most log colour seen within slide_mm (CV_32FC3; +-inf where none
  // was), and the weighted sums of the mean log colour.
  cv::Mat low_, high_;
  cv::Mat log_sum_, weight_sum_;
};

}  // namespace facecap
