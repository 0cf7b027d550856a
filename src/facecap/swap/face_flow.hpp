#pragma once
// The dense optical flow of a target face's window between consecutive
// frames, back to the last frame and ahead from it again (DIS, Kroeger et
// al., ECCV 2016; OpenCV's medium preset): what MovingCover reads to tell a
// hand moving over the face from the face itself.
//
// It needs only the two frames and where the face is (a swap computes it
// on another thread, beside the last frame's swap: FramePreparation); the
// two flows run on two cores where both are free.
#include <memory>
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/geometry.hpp"
#include "facecap/core/mesh.hpp"

namespace facecap {

// A window of the image scaled by `scale` (as cv::resize maps pixel
// centres): its pixel coordinates for an image point.
struct ScaledWindow {
  cv::Point origin;
  float scale = 1;
  Vec2f operator()(const Vec2f& p) const {
    return {(p.x() - origin.x + 0.5f) * scale - 0.5f, (p.y() - origin.y + 0.5f) * scale - 0.5f};
  }
  // The camera that sees the window.
  PinholeCamera camera(const PinholeCamera& c) const { return c.cropped(origin.x, origin.y).resized(scale); }
};

// One frame's flows over `window` (CV_32FC2, in the window's pixels): from
// this frame back to the last, and from the last ahead to this one.
struct FlowPair {
  int index = -1;  // the frame's number (FaceFlow::next's frame_index)
  ScaledWindow window;
  cv::Mat back, ahead;
  bool empty() const { return back.empty(); }
};

// The image box around the vertices of `skin` that face the camera (as a
// texel must, 0.2 of head-on, for unshade_face to see it), grown by
// `margin` px and cut to `image`; empty where none does.
cv::Rect facing_box(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size image,
                    int margin);

class FaceFlow {
 public:
  // The face's window is scaled to at most `flow_width` px across.
  explicit FaceFlow(int flow_width = 192);
  ~FaceFlow();
  FaceFlow(FaceFlow&&) noexcept;
  FaceFlow& operator=(FaceFlow&&) noexcept;

  // The flows between the last frame given and `frame` (BGR8) over both
  // frames' face boxes; empty for the first frame, after reset(), where
  // `frame_index` does not follow the last frame's (-1: unknown, taken to
  // follow), or where the frames differ in size or the face has no box.
  FlowPair next(const cv::Mat& frame, const cv::Rect& face_box, int frame_index = -1);

  // Takes `frame` as the last frame, as next() does, without the flows:
  // for a frame where nothing needs them, the next frame's are still
  // between consecutive frames.
  void skip(const cv::Mat& frame, const cv::Rect& face_box, int frame_index = -1);

  // Forget the last frame.
  void reset();

 private:
  struct State;
  // Starts afresh where `frame_index` does not follow the last frame's;
  // `frame` in grey.
  cv::Mat grey_following(const cv::Mat& frame, int frame_index);
  void remember(cv::Mat grey, const cv::Rect& face_box);
  int flow_width_;
  std::unique_ptr<State> state_;
};

}  // namespace facecap
