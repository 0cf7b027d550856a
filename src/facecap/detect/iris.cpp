#include "facecap/detect/iris.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

namespace facecap {

namespace {

// Every eye is searched at this width (corner to corner), in pixels.
constexpr double kEyeWidthPx = 48.0;

// An eye within this of level (15 degrees) is searched along the image's
// axes, as it always was: along its own axis, the synthetic renders' nearly
// upright heads (`eval track --synthetic 90`, true landmarks, seeds 1-4) had
// their irises 1.65 / 1.19 / 1.50 / 2.13 -> 1.71 / 1.27 / 1.57 / 2.06 px off
// and gaze errors 6.8 / 2.3 / 2.3 / 5.2 -> 7.0 / 2.4 / 2.5 / 5.3 degrees.
constexpr double kLevelEyeRadians = 15.0 * 3.14159265358979323846 / 180.0;

// Vertex of the parabola through (-1, a), (0, b), (1, c): a sub-pixel offset in [-0.5, 0.5].
double parabola_peak(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  if (!(curvature < 0.0)) return 0.0;
  return std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
}

// Where an eye's patch comes from. Its axes: x along the eye (corner 0 to
// 3), y across it, or the image's own for an eye within kLevelEyeRadians of
// level; patch coordinates are the image point's along them. The box about the six landmarks
// in those coordinates, with a margin of 0.15 of the eye's width (to hi: the
// far corner, which must lie inside the image), starts at the whole (x0, y0)
// and is resampled to `size`. An ellipse narrowed along the patch's x is
// then narrowed along the eye, however the face is rolled. (With the axes
// drawn to the image's within 15 degrees of level, as the jaw's silhouette
// direction is, an eye rolled 60 degrees was searched 15 degrees askew and
// its iris found 2.2 px off; not done.)
struct EyeWindow {
  Vec2d along = Vec2d(1, 0), across = Vec2d(0, 1);  // the patch's axes in the image
  double x0 = 0, y0 = 0, scale = 1;
  Vec2d hi = Vec2d::Zero();
  cv::Size size;
  // A point's coordinates along the patch's axes, and the image point of such coordinates.
  Vec2d local(const Vec2d& image) const { return {image.dot(along), image.dot(across)}; }
  Vec2d image(const Vec2d& local) const { return local.x() * along + local.y() * across; }
  // The image point of patch pixel (u, v).
  Vec2d at(const Vec2d& patch) const { return image(Vec2d(x0, y0) + patch / scale); }
  // The patch's last pixel along each axis (it may pass `hi` by a pixel of the patch).
  Vec2d last() const { return Vec2d(x0 + (size.width - 1) / scale, y0 + (size.height - 1) / scale); }
};

EyeWindow eye_window(const std::array<Vec2d, kEyeLandmarks>& p) {
  const Vec2d eye = p[3] - p[0];
  const double width = eye.norm();
  EyeWindow w;
  if (std::abs(std::atan2(eye.y(), eye.x())) > kLevelEyeRadians) {
    w.along = eye / width;
    w.across = Vec2d(-w.along.y(), w.along.x());
  }
  Vec2d lo = w.local(p[0]), hi = lo;
  for (const Vec2d& q : p) {
    lo = lo.cwiseMin(w.local(q));
    hi = hi.cwiseMax(w.local(q));
  }
  const double margin = 0.15 * width;
  w.x0 = std::floor(lo.x() - margin);
  w.y0 = std::floor(lo.y() - margin);
  w.hi = hi + Vec2d(margin, margin);
  w.scale = kEyeWidthPx / width;
  w.size = cv::Size(static_cast<int>(std::ceil((w.hi.x() - w.x0) * w.scale)) + 1,
                    static_cast<int>(std::ceil((w.hi.y() - w.y0) * w.scale)) + 1);
  return w;
}

// The image's box about the window's corners (x0, y0) and `to` (in the
// window's coordinates).
std::pair<Vec2d, Vec2d> image_bounds(const EyeWindow& w, const Vec2d& to) {
  Vec2d lo = w.image(Vec2d(w.x0, w.y0)), hi = lo;
  for (const Vec2d& corner : {Vec2d(to.x(), w.y0), Vec2d(w.x0, to.y()), to}) {
    lo = lo.cwiseMin(w.image(corner));
    hi = hi.cwiseMax(w.image(corner));
  }
  return {lo, hi};
}

// One eye resampled to kEyeWidthPx from its window: pixel (u, v) is image
// point window.at(u, v), pixel centres at integers on both sides.
struct EyePatch {
  EyeWindow window;
  cv::Mat image;    // CV_32F grey levels
  cv::Mat outline;  // CV_8U, 255 inside the six landmarks
  cv::Mat visible;  // CV_32F, 1 inside the outline shrunk off the lid line and lashes
};

std::array<Vec2d, kEyeLandmarks> eye_points(const Landmarks& landmarks, int eye) {
  std::array<Vec2d, kEyeLandmarks> p;
  for (int k = 0; k < kEyeLandmarks; ++k) p[k] = landmarks[first_eye_landmark(eye) + k].cast<double>();
  return p;
}

// `origin`: where grey's first pixel lies in the image `p` is in.
std::optional<EyePatch> resample_eye(const cv::Mat& grey, const cv::Point& origin,
                                     const std::array<Vec2d, kEyeLandmarks>& p) {
  const EyeWindow w = eye_window(p);
  const auto [lo, hi] = image_bounds(w, w.hi);
  if (lo.x() < origin.x || lo.y() < origin.y || hi.x() > origin.x + grey.cols - 1 || hi.y() > origin.y + grey.rows - 1)
    return std::nullopt;
  EyePatch e;
  e.window = w;
  const cv::Size size = w.size;
  // Patch pixel = scale (local(grey pixel + origin) - (x0, y0)). Along the
  // image's axes, x0 and the origin are whole pixels: the same samples as
  // from the whole image.
  const Vec2d o = w.local(Vec2d(origin.x, origin.y));
  const cv::Matx23d to_eye(w.scale * w.along.x(), w.scale * w.along.y(), w.scale * (o.x() - w.x0),
                           w.scale * w.across.x(), w.scale * w.across.y(), w.scale * (o.y() - w.y0));
  cv::warpAffine(grey, e.image, to_eye, size, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  e.image.convertTo(e.image, CV_32F);

  constexpr int kShift = 4;  // sub-pixel polygon vertices
  std::vector<cv::Point> outline;
  for (const Vec2d& q : p) {
    const Vec2d l = w.local(q);
    outline.emplace_back(static_cast<int>(std::lround(w.scale * (l.x() - w.x0) * (1 << kShift))),
                         static_cast<int>(std::lround(w.scale * (l.y() - w.y0) * (1 << kShift))));
  }
  e.outline = cv::Mat::zeros(size, CV_8U);
  cv::fillPoly(e.outline, std::vector<std::vector<cv::Point>>{outline}, cv::Scalar(255), cv::LINE_8, kShift);
  const int shrink = static_cast<int>(std::lround(0.05 * kEyeWidthPx));
  cv::Mat shrunk;
  cv::erode(e.outline, shrunk, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * shrink + 1, 2 * shrink + 1)));
  shrunk.convertTo(e.visible, CV_32F, 1.0 / 255.0);
  return e;
}

struct Disc {
  Vec2d centre = Vec2d::Zero();  // patch pixels
  double radius = 0;
  double score = -1;
};

// Sums over discs by rows: with each row's running sums, a disc's sum is
// one difference per row it spans.
class DiscSums {
 public:
  explicit DiscSums(const cv::Mat& values) {
    cv::integral(values, prefix_, CV_64F);  // (rows+1) x (cols+1); row r+1 holds the sums of rows 0..r
  }
  // Sum over the pixels of `rows` (row offset, half width) around (u, v);
  // parts outside the patch count as zero.
  double sum(int u, int v, const std::vector<std::pair<int, int>>& rows) const {
    double total = 0.0;
    const int width = prefix_.cols - 1, height = prefix_.rows - 1;
    for (const auto& [dy, half] : rows) {
      const int y = v + dy;
      if (y < 0 || y >= height) continue;
      const int x0 = std::max(0, u - half), x1 = std::min(width, u + half + 1);
      if (x1 <= x0) continue;
      // Row y alone: the integral's difference between rows y+1 and y.
      total += (prefix_.at<double>(y + 1, x1) - prefix_.at<double>(y + 1, x0)) -
               (prefix_.at<double>(y, x1) - prefix_.at<double>(y, x0));
    }
    return total;
  }

 private:
  cv::Mat prefix_;
};

// The dark disc that explains most of the visible eye's grey-level variance
// (Otsu's between-class variance: n_in n_out (m_out - m_in)^2 / (n^2 var)),
// over candidate centres inside the outline and the given radii (patch
// pixels), each disc narrowed to `aspect` of its height (an iris seen from
// the side).
Disc darkest_disc(const EyePatch& e, const std::vector<double>& radii, double aspect) {
  const double n = cv::sum(e.visible)[0];
  Disc best;
  if (n < 20.0) return best;
  const cv::Mat masked = e.image.mul(e.visible);
  const double total = cv::sum(masked)[0];
  const double mean = total / n;
  const double n2_variance = std::max(1e-6, n * (cv::sum(masked.mul(e.image))[0] - n * mean * mean));
  const DiscSums counts(e.visible), sums(masked);
  const cv::Size size = e.image.size();
  cv::Mat best_scores;
  cv::Point best_at(-1, -1);
  for (const double radius : radii) {
    std::vector<std::pair<int, int>> rows;
    const int reach = static_cast<int>(std::floor(radius));
    double disc_area = 0.0;
    for (int dy = -reach; dy <= reach; ++dy) {
      const int half = static_cast<int>(std::floor(aspect * std::sqrt(radius * radius - dy * dy)));
      rows.emplace_back(dy, half);
      disc_area += 2 * half + 1;
    }
    cv::Mat scores(size, CV_32F, cv::Scalar(-1.0f));
    bool improved = false;
    for (int v = 0; v < size.height; ++v) {
      for (int u = 0; u < size.width; ++u) {
        if (!e.outline.at<uint8_t>(v, u)) continue;
        const double n_in = counts.sum(u, v, rows), n_out = n - n_in;
        if (n_in < 0.2 * disc_area || n_out < 0.1 * n) continue;
        const double sum_in = sums.sum(u, v, rows);
        const double mean_in = sum_in / n_in, mean_out = (total - sum_in) / n_out;
        if (mean_out <= mean_in) continue;
        const double c = n_in * n_out * (mean_out - mean_in) * (mean_out - mean_in) / n2_variance;
        scores.at<float>(v, u) = static_cast<float>(c);
        if (c > best.score) {
          best.score = c;
          best.radius = radius;
          best_at = {u, v};
          improved = true;
        }
      }
    }
    if (improved) best_scores = scores;
  }
  if (best_at.x < 0) return best;
  auto at = [&](int u, int v) {
    if (u < 0 || v < 0 || u >= size.width || v >= size.height) return -1.0;
    return static_cast<double>(best_scores.at<float>(v, u));
  };
  const int u = best_at.x, v = best_at.y;
  best.centre = Vec2d(u, v);
  if (at(u - 1, v) >= 0 && at(u + 1, v) >= 0) best.centre.x() += parabola_peak(at(u - 1, v), best.score, at(u + 1, v));
  if (at(u, v - 1) >= 0 && at(u, v + 1) >= 0) best.centre.y() += parabola_peak(at(u, v - 1), best.score, at(u, v + 1));
  return best;
}

}  // namespace

std::optional<IrisObservation> locate_iris(const cv::Mat& grey, const Landmarks& landmarks, int eye,
                                           const IrisExpectation& expected, const IrisOptions& options,
                                           const cv::Point& origin) {
  if (grey.empty() || grey.type() != CV_8UC1 || (eye != 0 && eye != 1)) return std::nullopt;
  const std::array<Vec2d, kEyeLandmarks> p = eye_points(landmarks, eye);
  const double width = (p[3] - p[0]).norm();
  if (!(width >= options.min_eye_width_px)) return std::nullopt;
  const double opening = 0.5 * ((p[1] - p[5]).norm() + (p[2] - p[4]).norm());
  if (opening < options.min_opening * width) return std::nullopt;

  const std::optional<EyePatch> patch = resample_eye(grey, origin, p);
  if (!patch) return std::nullopt;
  std::vector<double> radii;
  if (expected.radius_px > 0.0) {
    for (const double f : options.radius_factors) radii.push_back(f * expected.radius_px * patch->window.scale);
  } else {
    for (const double share : options.radius_shares) radii.push_back(share * kEyeWidthPx);
  }
  const Disc disc = darkest_disc(*patch, radii, std::clamp(expected.aspect, 0.3, 1.0));
  if (disc.score < options.min_score) return std::nullopt;

  IrisObservation out;
  out.centre = patch->window.at(disc.centre);
  out.radius = disc.radius / patch->window.scale;
  out.score = disc.score;
  return out;
}

cv::Rect eye_crop(const cv::Size& image, const Landmarks& landmarks) {
  cv::Rect crop;
  for (int eye = 0; eye < 2; ++eye) {
    const EyeWindow w = eye_window(eye_points(landmarks, eye));
    const auto [first, last] = image_bounds(w, w.last());
    if (!first.allFinite() || !last.allFinite()) continue;
    // From a pixel before the patch's first to two past its last: the
    // bilinear samples' neighbours, whatever way they round.
    const cv::Point from(static_cast<int>(std::floor(first.x())) - 1, static_cast<int>(std::floor(first.y())) - 1);
    const cv::Point to(static_cast<int>(std::floor(last.x())) + 3, static_cast<int>(std::floor(last.y())) + 3);
    crop |= cv::Rect(from, to);
  }
  return crop & cv::Rect(cv::Point(0, 0), image);
}

}  // namespace facecap
