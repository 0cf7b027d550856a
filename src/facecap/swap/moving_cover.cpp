#include "facecap/swap/moving_cover.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/core/frame_sequence.hpp"
#include "facecap/core/image_sampling.hpp"
#include "facecap/core/parallel.hpp"
#include "facecap/swap/face_flow.hpp"
#include "facecap/swap/occlusion_mask.hpp"

namespace facecap {

namespace {

// About this many of the skin's vertices sample the disagreement the
// whole face shares.
constexpr int kSampledVertices = 1500;
// Rounds of the trimmed least squares.
constexpr int kFitRounds = 4;

// Each texel's image position (CV_32FC2) and depth in cm (CV_32F, 0 where
// no triangle covers the texel).
void texel_positions(const UvTexelMap& map, const std::vector<Triangle>& triangles, const Positions& points,
                     const PinholeCamera& camera, cv::Mat& image_xy, cv::Mat& depth) {
  image_xy.create(map.size, map.size, CV_32FC2);
  depth.create(map.size, map.size, CV_32F);
  parallel_for(
      map.size,
      [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          auto* xy = image_xy.ptr<cv::Vec2f>(y);
          float* z = depth.ptr<float>(y);
          for (int x = 0; x < map.size; ++x) {
            const int i = map.index(x, y);
            if (map.triangle[i] < 0) {
              xy[x] = {0, 0};
              z[x] = 0;
              continue;
            }
            const Vec3f p = map.interpolate(triangles, points, i);
            const Vec2f q = camera.project(p);
            xy[x] = {q.x(), q.y()};
            z[x] = p.z() > 0 ? p.z() : 0;
          }
        }
      },
      16);
}

// The image box around the texels `seen` marks, grown by `margin` px.
cv::Rect seen_bounds(const cv::Mat& image_xy, const cv::Mat& seen, int margin) {
  float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
  for (int y = 0; y < seen.rows; ++y) {
    const auto* xy = image_xy.ptr<cv::Vec2f>(y);
    const float* s = seen.ptr<float>(y);
    for (int x = 0; x < seen.cols; ++x) {
      if (s[x] <= 0) continue;
      x0 = std::min(x0, xy[x][0]);
      x1 = std::max(x1, xy[x][0]);
      y0 = std::min(y0, xy[x][1]);
      y1 = std::max(y1, xy[x][1]);
    }
  }
  if (x1 < x0) return {};
  return cv::Rect(cv::Point(int(std::floor(x0)) - margin, int(std::floor(y0)) - margin),
                  cv::Point(int(std::ceil(x1)) + margin + 1, int(std::ceil(y1)) + margin + 1));
}

// A sampled vertex's position this frame and its disagreement (pixels):
// where the flow says its pixel was in the last frame, less where the
// model says the vertex was.
struct VertexSample {
  Vec2f at, disagreement;
};

// d(p) = A [p - origin; 1] (2 x 3).
struct AffineField {
  Eigen::Matrix<float, 2, 3> a = Eigen::Matrix<float, 2, 3>::Zero();
  Vec2f origin = Vec2f::Zero();
  Vec2f operator()(const Vec2f& p) const {
    const Vec2f q = p - origin;
    return a * Vec3f(q.x(), q.y(), 1.0f);
  }
};

// The tracking's own error moves the whole face a little (most where a
// hand hides the landmarks): the affine field over the image that the
// face's disagreements share is the tracking's, not a cover's. Fitted by
// least squares, then refitted to the samples within twice the median
// distance of the last fit (at least half a pixel), three times: a cover's
// samples, which disagree by more, fall out.
AffineField shared_disagreement(const std::vector<VertexSample>& samples) {
  AffineField field;
  const int m = int(samples.size());
  if (m < 3) return field;
  for (const VertexSample& s : samples) field.origin += s.at;
  field.origin /= float(m);
  std::vector<float> distance(m, 0.0f);
  float limit = std::numeric_limits<float>::max();
  for (int round = 0; round < kFitRounds; ++round) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, 2> rhs = Eigen::Matrix<double, 3, 2>::Zero();
    for (int i = 0; i < m; ++i) {
      if (distance[i] > limit) continue;
      const Vec2f q = samples[i].at - field.origin;
      const Eigen::Vector3d p(q.x(), q.y(), 1.0);
      normal += p * p.transpose();
      rhs += p * samples[i].disagreement.cast<double>().transpose();
    }
    const Eigen::LDLT<Eigen::Matrix3d> solve(normal);
    if (solve.info() != Eigen::Success || !(solve.rcond() > 1e-9)) break;
    field.a = solve.solve(rhs).transpose().cast<float>();
    for (int i = 0; i < m; ++i) distance[i] = (samples[i].disagreement - field(samples[i].at)).norm();
    std::vector<float> sorted = distance;
    std::nth_element(sorted.begin(), sorted.begin() + m / 2, sorted.end());
    limit = std::max(0.5f, 2.0f * sorted[m / 2]);
  }
  return field;
}

}  // namespace

struct MovingCover::State {
  explicit State(int flow_width) : flow(flow_width) {}
  TriangleMesh skin;
  UvTexelMap map;
  double texels_per_mm = 0;
  std::vector<int> sampled;       // the vertices that sample the shared disagreement
  std::vector<int> vertex_texel;  // per vertex, a texel at its UV (-1: none)
  FaceFlow flow;
  // The last frame: its texels' and sampled vertices' image positions, and
  // its evidence drawn into the image over its face box.
  cv::Mat image_xy;
  Eigen::Matrix2Xf sampled_xy;  // the sampled vertices', in their order
  cv::Mat evidence_image;       // at evidence_window's scale (empty: no evidence)
  ScaledWindow evidence_window;
  FrameSequence sequence;  // the frames' numbers
  bool measured = false;   // the last update() ran the flow
};

namespace {

const MovingCoverOptions& checked(const MovingCoverOptions& o) {
  if (!(o.min_motion_mm > 0 && o.half_life_frames > 0 && o.flow_width >= 16 && o.min_extent_mm >= 0))
    throw Error("moving cover: needs a positive motion and half-life, and a flow window of 16 px or more");
  return o;
}

}  // namespace

MovingCover::MovingCover(const TriangleMesh& skin, const MillimetreGrid& grid, MovingCoverOptions options)
    : options_(checked(options)), state_(std::make_unique<State>(options_.flow_width)) {
  State& s = *state_;
  s.skin = skin;
  s.map = grid.map;
  s.texels_per_mm = grid.texels_per_mm;
  s.vertex_texel.assign(skin.num_vertices, -1);
  for (size_t t = 0; t < skin.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int v = skin.triangles[t][c];
      if (s.vertex_texel[v] >= 0) continue;
      const Vec2f texel = uv_to_texel(skin.uvs[skin.triangle_uvs[t][c]], grid.map.size);
      const int x = std::clamp(int(std::lround(texel.x())), 0, grid.map.size - 1);
      const int y = std::clamp(int(std::lround(texel.y())), 0, grid.map.size - 1);
      s.vertex_texel[v] = grid.map.index(x, y);
    }
  }
  std::vector<int> used;
  for (int v = 0; v < skin.num_vertices; ++v)
    if (s.vertex_texel[v] >= 0) used.push_back(v);
  const size_t stride = std::max<size_t>(1, used.size() / kSampledVertices);
  for (size_t i = 0; i < used.size(); i += stride) s.sampled.push_back(used[i]);
}

MovingCover::~MovingCover() = default;
MovingCover::MovingCover(MovingCover&&) noexcept = default;
MovingCover& MovingCover::operator=(MovingCover&&) noexcept = default;

bool MovingCover::measured_motion() const { return state_->measured; }

void MovingCover::reset() {
  state_->flow.reset();
  state_->image_xy = cv::Mat();
  state_->evidence_image = cv::Mat();
}

cv::Mat MovingCover::update(const cv::Mat& frame, const Positions& points, const PinholeCamera& camera,
                            const cv::Mat& seen, int frame_index, bool colour_changed) {
  State& s = *state_;
  // Motion is measured between consecutive frames only.
  if (!s.sequence.follows(frame_index)) reset();
  const int n = s.map.size;
  cv::Mat evidence(n, n, CV_32F, cv::Scalar(0));
  cv::Mat image_xy, depth;
  texel_positions(s.map, s.skin.triangles, points, camera, image_xy, depth);
  Eigen::Matrix2Xf sampled_xy(2, s.sampled.size());
  for (size_t k = 0; k < s.sampled.size(); ++k) sampled_xy.col(k) = camera.project(Vec3f(points.col(s.sampled[k])));
  const cv::Rect frame_rect(0, 0, frame.cols, frame.rows);
  const cv::Rect face_box = seen_bounds(image_xy, seen, 8) & frame_rect;

  // Without a new colour and with nothing to carry, the evidence is none:
  // nothing moves fast enough for a new cover, and growth needs a seed.
  const cv::Rect flow_box = facing_box(s.skin, points, camera, frame.size(), 8);
  const bool needs_flow = colour_changed || !s.evidence_image.empty();
  FlowPair flow;
  if (needs_flow)
    flow = s.flow.next(frame, flow_box, frame_index);
  else
    s.flow.skip(frame, flow_box, frame_index);
  s.measured = !flow.empty();
  if (!flow.empty() && !s.image_xy.empty() && face_box.area() > 0) {
    const ScaledWindow& window = flow.window;
    const cv::Mat &back = flow.back, &ahead = flow.ahead;
    // The flow at an image point, in the flow's pixels.
    auto flow_at = [&](const cv::Mat& field, const Vec2f& p) {
      const Vec2f q = window(p);
      const cv::Vec2f f = sample_bilinear_channels<2>(field, q.x(), q.y());
      return Vec2f(f[0], f[1]);
    };
    // The last frame's evidence at an image point (0 outside its window).
    auto carried_at = [&](const Vec2f& p) {
      if (s.evidence_image.empty()) return 0.0f;
      const Vec2f q = s.evidence_window(p);
      if (q.x() < 0 || q.y() < 0 || q.x() > s.evidence_image.cols - 1 || q.y() > s.evidence_image.rows - 1) return 0.0f;
      return sample_bilinear_channels<1>(s.evidence_image, q.x(), q.y())[0];
    };

    // What the whole face's disagreement shares, from sampled vertices
    // that this frame sees and that no cover held in the last.
    std::vector<VertexSample> samples;
    for (size_t k = 0; k < s.sampled.size(); ++k) {
      if (reinterpret_cast<const float*>(seen.data)[s.vertex_texel[s.sampled[k]]] <= 0) continue;
      const Vec2f at = sampled_xy.col(k);
      const Vec2f from = at + flow_at(back, at) / window.scale;
      if (carried_at(from) >= kCoveringEvidence) continue;
      samples.push_back({at, from - s.sampled_xy.col(k)});
    }
    const AffineField shared = shared_disagreement(samples);

    // Per texel: moving across the face (`slow`, and `fast` for a cover not
    // found before), and the last frame's evidence carried along the flow,
    // fading, where the flow holds both ways.
    const float keep = std::exp2(-1.0f / options_.half_life_frames);
    const float mm_per_px_cm = 10.0f / float(camera.focal);  // times depth (cm): mm per pixel
    cv::Mat slow(n, n, CV_8U, cv::Scalar(0)), fast(n, n, CV_8U, cv::Scalar(0));
    parallel_for(
        n,
        [&](int y0, int y1) {
          for (int y = y0; y < y1; ++y) {
            const auto* xy = image_xy.ptr<cv::Vec2f>(y);
            const auto* last_xy = s.image_xy.ptr<cv::Vec2f>(y);
            const float* z = depth.ptr<float>(y);
            const float* w = seen.ptr<float>(y);
            float* e = evidence.ptr<float>(y);
            uchar* is_slow = slow.ptr<uchar>(y);
            uchar* is_fast = fast.ptr<uchar>(y);
            for (int x = 0; x < n; ++x) {
              if (w[x] <= 0 || z[x] <= 0) continue;
              const Vec2f at(xy[x][0], xy[x][1]);
              // Where the flow says the pixel was in the last frame, and how
              // far the flow forward from there misses it again, against the
              // tolerance of Sundaram, Brox and Keutzer (ECCV 2010): |w +
              // w'|^2 < share (|w|^2 + |w'|^2) + 0.5 px^2 in the flow's
              // pixels, share 0.01 theirs. It fails where the pixel was
              // hidden in one of the frames (the mouth opening or closing,
              // what a hand uncovers): there the flow is the smoothing's guess.
              const Vec2f back_w = flow_at(back, at);
              const Vec2f from = at + back_w / window.scale;
              const Vec2f ahead_w = flow_at(ahead, from);
              const float miss = (back_w + ahead_w).squaredNorm();
              const float length = back_w.squaredNorm() + ahead_w.squaredNorm();
              const bool holds = miss < 0.01f * length + 0.5f;
              // Where the flow says the pixel was, less where the model says
              // its surface point was and what the whole face shares.
              const float moved_mm =
                  (from - Vec2f(last_xy[x][0], last_xy[x][1]) - shared(at)).norm() * z[x] * mm_per_px_cm;
              if (holds && moved_mm > options_.min_motion_mm) is_slow[x] = 255;
              // A hand moving fast leaves its own flow imprecise (little
              // texture, large steps): a new cover needs a round trip within
              // a quarter of the flow's length only, which what it uncovers
              // fails (the flow there goes with the hand both ways).
              if (moved_mm > options_.new_cover_motion_mm && miss < 0.25f * length + 0.5f) is_fast[x] = 255;
              if (holds) e[x] = keep * carried_at(from);
            }
          }
        },
        16);
    // A new cover moves fast over min_extent_mm at least (narrower or
    // slower: the tracking's own slips, at the lips most); a cover already
    // found grows into what moves slower beside it (hysteresis, as Canny's
    // edges).
    const int radius = int(std::lround(0.5 * options_.min_extent_mm * s.texels_per_mm));
    if (radius > 0)
      cv::morphologyEx(fast, fast, cv::MORPH_OPEN,
                       cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
    slow |= fast;
    const cv::Mat seeds = fast | ((evidence >= kCoveringEvidence) & slow);
    cv::Mat labels;
    const int count = cv::connectedComponents(slow, labels, 8, CV_32S);
    std::vector<uchar> seeded(count, 0);
    const auto* label = reinterpret_cast<const int*>(labels.data);
    for (int i = 0; i < n * n; ++i)
      if (seeds.data[i]) seeded[label[i]] = 1;
    seeded[0] = 0;  // the background
    auto* e = reinterpret_cast<float*>(evidence.data);
    for (int i = 0; i < n * n; ++i)
      if (seeded[label[i]]) e[i] = 1.0f;
  }
  s.image_xy = image_xy;
  s.sampled_xy = sampled_xy;
  // The evidence drawn into the image, at the flow's scale (the next
  // frame samples it where its flow says its pixels came from); none
  // drawn where none reaches one half (most frames: the drawing, a
  // rasterisation of the skin, took 2-3 ms a frame beside a 720p swap).
  // Evidence under one half is inert: what covers the face
  // (OcclusionMask::covered), the seeds above and the samples of the
  // shared disagreement all need one half, and carried evidence only
  // fades; without it the flow need not run (colour_changed).
  s.evidence_window = {face_box.tl(), std::min(1.0f, float(options_.flow_width) / float(std::max(1, face_box.width)))};
  const cv::Size evidence_size(std::max(1, int(std::lround(face_box.width * s.evidence_window.scale))),
                               std::max(1, int(std::lround(face_box.height * s.evidence_window.scale))));
  double strongest = 0;
  cv::minMaxLoc(evidence, nullptr, &strongest);
  s.evidence_image = face_box.area() > 0 && strongest >= kCoveringEvidence
                         ? cover_in_image(s.skin, points, s.evidence_window.camera(camera), evidence_size, evidence)
                         : cv::Mat();
  return evidence;
}

}  // namespace facecap
