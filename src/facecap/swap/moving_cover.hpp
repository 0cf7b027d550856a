#pragma once
// What moves across the target's face other than the face itself (a hand
// wiping an eye, fingers over the mouth), found by its motion where its
// colour gives it away no better than the skin's own: a hand in the same
// light as the face is the cover OcclusionMask's colour test cannot see.
// A departure from the paper, whose swap (§6.3) paints over what covers
// the face.
//
// Each frame, the dense optical flow (face_flow.hpp) from this frame's
// face window back to the last frame's says where each
// surface point's pixel came from; the tracked model says where the point
// itself was. What the whole face's disagreement shares (an affine field:
// the tracking a little off, most where a hand hides the landmarks) is
// taken out. A new cover disagrees by more than new_cover_motion_mm over
// min_extent_mm at least; a cover already found grows into what disagrees
// by more than min_motion_mm beside it (hysteresis). Where the flow back
// and forward again does not return to its pixel, the pixel was hidden in
// one of the frames (the mouth opening, what a hand uncovers) and the flow
// is a guess: growth and carrying need the round trip, a new cover only
// within a quarter of the flow's length (its own flow is rough). The last
// frame's evidence is carried along the flow, fading by half every
// half_life_frames frames: a hand that rests stays found for a while
// (evidence under one half counts for nothing, and is dropped). The
// lips' and the jaw's own motion, which the tracking follows a little
// late, is no cover on the talking heads of ../shared/data.
//
// Its cost at 720p alone (swap_bench BM_MovingCover720p): 7 ms a frame, of
// which the two flows take 3 on two cores (5 on one). A caller that knows
// nothing changed colour on the face (colour_change.hpp) skips the flows
// where no cover is being carried: most frames of a talking head. A swap
// runs it on another thread, beside the last frame's swap (FramePreparation), where
// on 2 cores it takes 3 to 5 times as long, sharing them
// (SwapOptions::moving_covers turns it off).
#include <memory>
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/render/uv_raster.hpp"
#include "facecap/swap/face_flow.hpp"

namespace facecap {

struct MovingCoverOptions {
  float min_motion_mm = 3.0f;        // the flow against the model's motion, per frame, beside a cover
  float new_cover_motion_mm = 6.0f;  // as much for a cover not found before
  float min_extent_mm = 8.0f;        // and over this width at least
  float half_life_frames = 48.0f;    // how fast evidence that is not renewed fades
  int flow_width = 192;              // the face window is scaled to at most this width for the flow
};

class MovingCover {
 public:
  // `skin` with UVs; `grid` the texel map the evidence lives on (the
  // OcclusionMask's).
  MovingCover(const TriangleMesh& skin, const MillimetreGrid& grid, MovingCoverOptions options = {});
  ~MovingCover();
  MovingCover(MovingCover&&) noexcept;
  MovingCover& operator=(MovingCover&&) noexcept;

  // This frame's evidence (CV_32F, 0..1, on the grid) from `frame` (BGR8)
  // and the target's skin vertices in camera space; `seen`: the grid's
  // texels the frame sees (CV_32F, > 0). `frame_index`: its number in the
  // video; one that does not follow the last frame's (a frame without a
  // face between) starts afresh, as reset() does; -1: unknown, taken to
  // follow. None on the first frame after construction or reset().
  // `colour_changed`: false where the caller knows that nothing on the
  // face changed colour since the last frame (ColourChange), so that
  // nothing new came across it: where no cover is being carried either,
  // the flows are skipped and the evidence is none, as they would find.
  cv::Mat update(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera, const cv::Mat& seen,
                 int frame_index = -1, bool colour_changed = true);

  // Forget the last frame.
  void reset();

  // Whether the last update() ran the optical flow (not on the first frame,
  // nor where it was told nothing changed colour and carried nothing).
  bool measured_motion() const;

 private:
  struct State;
  MovingCoverOptions options_;
  std::unique_ptr<State> state_;
};

}  // namespace facecap
