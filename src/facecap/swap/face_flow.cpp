#include "facecap/swap/face_flow.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <utility>

#include "facecap/core/error.hpp"
#include "facecap/core/frame_sequence.hpp"
#include "facecap/core/parallel.hpp"

namespace facecap {

cv::Rect facing_box(const TriangleMesh& skin, const Positions& points, const PinholeCamera& camera, cv::Size image,
                    int margin) {
  const Positions normals = vertex_normals(points, skin.triangles);
  std::vector<bool> used(skin.num_vertices, false);
  for (const Triangle& t : skin.triangles)
    for (const int v : t) used[v] = true;
  float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
  for (int v = 0; v < skin.num_vertices; ++v) {
    const Vec3f p = points.col(v);
    if (!used[v] || !(p.z() > 0) || !(view_facing(p, Vec3f(normals.col(v))) > 0.2f)) continue;
    const Vec2f q = camera.project(p);
    x0 = std::min(x0, q.x());
    x1 = std::max(x1, q.x());
    y0 = std::min(y0, q.y());
    y1 = std::max(y1, q.y());
  }
  if (!(x1 >= x0 && y1 >= y0) || !(x1 - x0 < 1e6f && y1 - y0 < 1e6f)) return {};
  const cv::Rect box(cv::Point(int(std::floor(x0)) - margin, int(std::floor(y0)) - margin),
                     cv::Point(int(std::ceil(x1)) + margin + 1, int(std::ceil(y1)) + margin + 1));
  return box & cv::Rect(0, 0, image.width, image.height);
}

struct FaceFlow::State {
  cv::Ptr<cv::DISOpticalFlow> back, ahead;  // one each: the two run at once
  cv::Mat grey;                             // the last frame's
  cv::Rect box;                             // its face box
  FrameSequence sequence;                   // the frames' numbers
};

FaceFlow::FaceFlow(int flow_width) : flow_width_(flow_width), state_(std::make_unique<State>()) {
  if (flow_width_ < 16) throw Error("face flow: needs a flow window of 16 px or more");
  // The medium preset: the fast ones, at this window, found a sixth as much
  // of a skin-coloured hand (SwapJob.AHandOfTheSkinsOwnColourStaysInFront).
  // Without its variational refinement the flow is 40 % cheaper and keeps
  // more of that synthetic hand (0.71 against 0.62), but finds less of a
  // real one (emotions_pexels: 8.6 % of the face covered against 12.3 %,
  // self-swap mean 11.37 against 11.15).
  state_->back = cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_MEDIUM);
  state_->ahead = cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_MEDIUM);
}

FaceFlow::~FaceFlow() = default;
FaceFlow::FaceFlow(FaceFlow&&) noexcept = default;
FaceFlow& FaceFlow::operator=(FaceFlow&&) noexcept = default;

void FaceFlow::reset() {
  state_->grey = cv::Mat();
  state_->box = cv::Rect();
}

cv::Mat FaceFlow::grey_following(const cv::Mat& frame, int frame_index) {
  if (!state_->sequence.follows(frame_index)) reset();
  cv::Mat grey;
  cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

void FaceFlow::remember(cv::Mat grey, const cv::Rect& face_box) {
  state_->grey = std::move(grey);
  state_->box = face_box;
}

void FaceFlow::skip(const cv::Mat& frame, const cv::Rect& face_box, int frame_index) {
  remember(grey_following(frame, frame_index), face_box);
}

FlowPair FaceFlow::next(const cv::Mat& frame, const cv::Rect& face_box, int frame_index) {
  State& s = *state_;
  cv::Mat grey = grey_following(frame, frame_index);
  FlowPair out;
  out.index = frame_index;
  const cv::Rect frame_rect(0, 0, frame.cols, frame.rows);
  if (!s.grey.empty() && s.grey.size() == grey.size() && face_box.area() > 0) {
    const cv::Rect box = (face_box | s.box) & frame_rect;
    out.window = {box.tl(), std::min(1.0f, float(flow_width_) / float(box.width))};
    cv::Mat now_small, last_small;
    cv::resize(grey(box), now_small, cv::Size(), out.window.scale, out.window.scale, cv::INTER_AREA);
    cv::resize(s.grey(box), last_small, cv::Size(), out.window.scale, out.window.scale, cv::INTER_AREA);
    // Independent: each on a core of its own where one is free.
    parallel_for(
        2,
        [&](int b, int e) {
          for (int k = b; k < e; ++k) {
            if (k == 0)
              s.back->calc(now_small, last_small, out.back);
            else
              s.ahead->calc(last_small, now_small, out.ahead);
          }
        },
        1);
  }
  remember(std::move(grey), face_box);
  return out;
}

}  // namespace facecap
