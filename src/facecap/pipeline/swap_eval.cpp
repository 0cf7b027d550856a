#include "facecap/pipeline/swap_eval.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <span>

#include "facecap/core/error.hpp"
#include "facecap/core/rigid_alignment.hpp"
#include "facecap/core/statistics.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// The per-pixel errors, the mean absolute difference over the three 8-bit
// channels: a sum of 0..765 over 3, kept as a histogram of the sums so that
// the median is exact (a histogram of 0.05-wide bins returned a bin's
// centre, 0.025 above an error of exactly 3).
struct ErrorHistogram {
  std::vector<double> sums = std::vector<double>(3 * 255 + 1, 0.0);
  double total = 0, count = 0;
  void add(int channel_sum) {
    sums[std::clamp(channel_sum, 0, 3 * 255)] += 1;
    total += channel_sum;
    count += 1;
  }
  double mean() const { return count > 0 ? total / (3.0 * count) : 0; }
  // The lower median: the smallest error with at least half the pixels at or below it.
  double median() const {
    double run = 0;
    for (size_t k = 0; k < sums.size(); ++k) {
      run += sums[k];
      if (run >= 0.5 * count && count > 0) return k / 3.0;
    }
    return 0;
  }
};

// Boxes around the mouth (landmarks 48-67) and the eyes with their brows
// (17-26, 36-47), grown a little, for splitting an error by region.
struct FeatureBoxes {
  cv::Rect2f mouth, eyes;

  FeatureBoxes(const Landmarks& points, const cv::Point2f& origin) {
    // Landmarks first..last, as a rectangle relative to `origin`.
    auto range = [&](int first, int last) {
      const Box b = bounding_box(std::span<const Vec2f>(points).subspan(first, last - first + 1));
      return cv::Rect2f(b.x - origin.x, b.y - origin.y, b.width, b.height);
    };
    auto grown = [](const cv::Rect2f& r, float grow_x, float grow_y) {
      return cv::Rect2f(r.x - grow_x * r.width, r.y - grow_y * r.height, (1 + 2 * grow_x) * r.width,
                        (1 + 2 * grow_y) * r.height);
    };
    mouth = grown(range(48, 67), 0.2f, 0.3f);
    eyes = grown(range(17, 26) | range(36, 47), 0.05f, 0.15f);
  }
  // 0 mouth, 1 eyes (the mouth's box wins where they meet), 2 the rest.
  int region(int x, int y) const {
    const cv::Point2f p{float(x), float(y)};
    return mouth.contains(p) ? 0 : eyes.contains(p) ? 1 : 2;
  }
};

// An identity's neutral face region.
Positions neutral_face(const FaceModel& model, const Eigen::VectorXf& identity) {
  return model.evaluate(identity, Eigen::VectorXf(), regions::kFace);
}

// Mean distance in mm between two face regions after a similarity alignment.
double shape_distance_mm(const Positions& a, const Positions& b) { return 10.0 * aligned_mean_distance(a, b, true); }

// The identity of one frame fitted as a photo (as the source is), or nothing
// when no face is found in it.
std::optional<Eigen::VectorXf> photo_identity(const FaceModel& model, const cv::Mat& image, const fs::path& file) {
  write_image(file, image);
  try {
    return reconstruct_source(model, file.string(), true, 1).face.identity;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace

double seam_ratio(const cv::Mat& image, const cv::Mat& alpha) {
  if (image.empty() || alpha.empty()) return 0;
  // The blend's outer boundary: the eyes and the mouth, where the target's
  // own show through the holes of the face mesh by design, count as inside.
  cv::Mat padded;
  cv::copyMakeBorder(cv::Mat(alpha > 0.01f), padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::floodFill(padded, cv::Point(0, 0), cv::Scalar(128));
  const cv::Mat mask = padded(cv::Rect(1, 1, alpha.cols, alpha.rows)) != 128;
  cv::Mat grey, gx, gy, magnitude;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Sobel(grey, gx, CV_32F, 1, 0);
  cv::Sobel(grey, gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, magnitude);
  auto eroded = [&](int r) {
    cv::Mat out;
    cv::erode(mask, out, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
    return out;
  };
  const cv::Mat edge = mask & ~eroded(1);  // the outermost pixels the blend touches
  const cv::Mat inside = eroded(6) & ~eroded(10);
  if (cv::countNonZero(edge) == 0 || cv::countNonZero(inside) == 0) return 0;
  const double on_edge = cv::mean(magnitude, edge)[0], within = cv::mean(magnitude, inside)[0];
  return within > 1e-6 ? on_edge / within : 0;
}

HueBeyond hue_beyond_target(const cv::Mat& output, const cv::Mat& target, const cv::Mat& alpha) {
  constexpr int kMinPixels = 100;
  constexpr float kMinLevel = 16.0f, kMargin = 0.05f, kLowShare = 0.005f;
  // Opponent colours over the pixel's level: a darker pixel of the same hue
  // has the same ones (in grey levels, B - R and 2G - R - B shrink toward 0
  // as a pixel darkens, so a deeper shadow would read as a bluer one).
  const auto opponents = [](const cv::Vec3b& pixel) -> std::optional<std::array<float, 2>> {
    const float b = pixel[0], g = pixel[1], r = pixel[2], level = (b + g + r) / 3;
    if (level < kMinLevel) return std::nullopt;  // too dark to have a hue
    return std::array<float, 2>{(b - r) / level, (2 * g - r - b) / level};
  };
  std::array<std::vector<float>, 2> target_opponents;
  std::vector<std::array<float, 2>> output_opponents;
  size_t face_pixels = 0;
  for (int y = 0; y < alpha.rows; ++y) {
    const float* a = alpha.ptr<float>(y);
    const auto* t = target.ptr<cv::Vec3b>(y);
    const auto* o = output.ptr<cv::Vec3b>(y);
    for (int x = 0; x < alpha.cols; ++x) {
      if (!(a[x] > 0.5f)) continue;
      ++face_pixels;
      if (const auto c = opponents(t[x])) {
        for (int k = 0; k < 2; ++k) target_opponents[k].push_back((*c)[k]);
      }
      if (const auto c = opponents(o[x])) output_opponents.push_back(*c);
    }
  }
  HueBeyond h;
  if (target_opponents[0].size() < kMinPixels) return h;
  std::array<float, 2> low, high;
  for (int k = 0; k < 2; ++k) {
    low[k] = quantile(target_opponents[k], kLowShare) - kMargin;
    high[k] = quantile(target_opponents[k], 1 - kLowShare) + kMargin;
  }
  size_t cool = 0, warm = 0;
  for (const auto& c : output_opponents) {
    cool += c[0] > high[0] || c[1] > high[1];
    warm += c[0] < low[0] || c[1] < low[1];
  }
  h.cool = double(cool) / face_pixels;
  h.warm = double(warm) / face_pixels;
  return h;
}

SwapSelfEval evaluate_swap_self(const FaceModel& model, const std::string& video, const SwapJobOptions& options,
                                int source_frames) {
  const TempDir temp("facecap-eval-swap");
  // The first frame as the source photo, or the first frames as a folder of photos.
  if (source_frames < 1) throw Error("--source-frames must be at least 1");
  auto input = open_input(video);
  const fs::path folder = temp.path() / "source";
  fs::create_directories(folder);
  for (int i = 0; i < source_frames; ++i) {
    Frame frame;
    if (!input->read(frame) || frame.image.empty()) {
      if (i == 0) throw Error("cannot read the first frame of " + video);
      break;
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    const fs::path file = folder / name;
    write_image(file, frame.image);
  }
  const fs::path source = source_frames > 1 ? folder : folder / "frame_000000.png";

  SwapSelfEval r;
  ErrorHistogram errors;
  std::array<double, 3> region_sum{}, region_count{};
  SwapJobOptions o = options;
  o.source_frames = source_frames;
  o.on_frame = [&](const CapturedFrame& target, const SwappedFrame& result) {
    if (target.index == 0 || result.alpha.empty()) return;
    const cv::Mat truth = target.image(result.window), made = result.image(result.window);
    const FeatureBoxes boxes(target.fit.observed, cv::Point2f(float(result.window.x), float(result.window.y)));
    for (int y = 0; y < result.window.height; ++y) {
      const auto* t = truth.ptr<cv::Vec3b>(y);
      const auto* m = made.ptr<cv::Vec3b>(y);
      const float* a = result.alpha.ptr<float>(y);
      for (int x = 0; x < result.window.width; ++x) {
        if (a[x] <= 0.5f) continue;
        const int channel_sum = std::abs(t[x][0] - m[x][0]) + std::abs(t[x][1] - m[x][1]) + std::abs(t[x][2] - m[x][2]);
        errors.add(channel_sum);
        const float e = channel_sum / 3.0f;
        const int region = boxes.region(x, y);
        region_sum[region] += e;
        region_count[region] += 1;
      }
    }
    ++r.frames;
    r.covered_mean += result.covered;
    r.covered_max = std::max(r.covered_max, result.covered);
  };
  const SwapSummary s = run_swap(model, source.string(), video, temp.path() / "self_swap.mp4", o);
  r.source_frames_used = s.source.frames_used;
  r.photometric_median = errors.median();
  r.photometric_mean = errors.mean();
  r.face_pixels_per_frame = r.frames > 0 ? errors.count / r.frames : 0;
  r.covered_mean = r.frames > 0 ? r.covered_mean / r.frames : 0;
  for (int k = 0; k < 3; ++k) {
    r.regions[k].mean = region_count[k] > 0 ? region_sum[k] / region_count[k] : 0;
    r.regions[k].share = errors.count > 0 ? region_count[k] / errors.count : 0;
  }
  r.timings = s.timings;
  return r;
}

SwapPairEval evaluate_swap_pair(const FaceModel& model, const std::string& photo, const std::string& video,
                                const SwapJobOptions& options, const fs::path& output) {
  std::optional<TempDir> temp;
  fs::path out = output;
  if (out.empty()) {
    temp.emplace("facecap-eval-swap");
    out = temp->path() / "swap.mp4";
  }
  SwapPairEval r;
  std::vector<Eigen::VectorXf> target_weights;
  double seams = 0, seams_target = 0;
  int seam_frames = 0;
  SwapJobOptions o = options;
  o.on_frame = [&](const CapturedFrame& target, const SwappedFrame& result) {
    target_weights.push_back(target.status == TrackStatus::kLost ? Eigen::VectorXf() : target.fit.expression);
    if (result.alpha.empty()) return;
    seams += seam_ratio(result.image(result.window), result.alpha);
    seams_target += seam_ratio(target.image(result.window), result.alpha);
    const HueBeyond hue = hue_beyond_target(result.image(result.window), target.image(result.window), result.alpha);
    r.hue_beyond_cool += hue.cool;
    r.hue_beyond_warm += hue.warm;
    ++seam_frames;
    r.covered_mean += result.covered;
    r.covered_max = std::max(r.covered_max, result.covered);
  };
  const SwapSummary s = run_swap(model, photo, video, out, o);
  r.timings = s.timings;
  r.faces_in_source = s.source.faces_found;
  r.seam_ratio = seam_frames > 0 ? seams / seam_frames : 0;
  r.seam_ratio_target = seam_frames > 0 ? seams_target / seam_frames : 0;
  r.covered_mean = seam_frames > 0 ? r.covered_mean / seam_frames : 0;
  r.hue_beyond_cool = seam_frames > 0 ? r.hue_beyond_cool / seam_frames : 0;
  r.hue_beyond_warm = seam_frames > 0 ? r.hue_beyond_warm / seam_frames : 0;

  // Track the output again: whose face is it now, and does it do what the target did?
  std::vector<Eigen::VectorXf> output_weights;
  CaptureOptions c = options.capture;
  c.quiet = true;
  auto result = open_input(out.string());
  const CaptureSummary tracked = run_capture(model, *result, c, [&](const CapturedFrame& f) {
    output_weights.push_back(f.status == TrackStatus::kLost ? Eigen::VectorXf() : f.fit.expression);
  });
  const Eigen::VectorXf id_out = tracked.identity.identity.cast<float>();
  const Eigen::VectorXf id_src = s.source.face.identity;
  const Eigen::VectorXf id_tgt = s.target.identity.identity.cast<float>();
  r.identity_distance_output_source = (id_out - id_src).norm();
  r.identity_distance_output_target = (id_out - id_tgt).norm();
  r.identity_distance_source_target = (id_src - id_tgt).norm();

  // The same with every image fitted alike (one frame as a photo).
  {
    const TempDir alike("facecap-eval-alike");
    auto output_frames = open_input(out.string());
    auto target_frames = open_input(video);
    const Positions src_face = neutral_face(model, id_src);
    Frame o_frame, t_frame;
    for (int i = 0;
         r.identity_alike_frames < kAlikeIdentityFrames && output_frames->read(o_frame) && target_frames->read(t_frame);
         ++i) {
      if (i % 10 != 5) continue;
      const auto o_id = photo_identity(model, o_frame.image, alike.path() / "output.png");
      const auto t_id = photo_identity(model, t_frame.image, alike.path() / "target.png");
      if (!o_id || !t_id) continue;
      r.identity_alike_output_source += (*o_id - id_src).norm();
      r.identity_alike_output_target += (*o_id - *t_id).norm();
      r.identity_alike_source_target += (*t_id - id_src).norm();
      const Positions o_face = neutral_face(model, *o_id), t_face = neutral_face(model, *t_id);
      r.shape_alike_output_source_mm += shape_distance_mm(o_face, src_face);
      r.shape_alike_output_target_mm += shape_distance_mm(o_face, t_face);
      r.shape_alike_source_target_mm += shape_distance_mm(t_face, src_face);
      ++r.identity_alike_frames;
    }
    if (r.identity_alike_frames > 0) {
      r.identity_alike_output_source /= r.identity_alike_frames;
      r.identity_alike_output_target /= r.identity_alike_frames;
      r.identity_alike_source_target /= r.identity_alike_frames;
      r.shape_alike_output_source_mm /= r.identity_alike_frames;
      r.shape_alike_output_target_mm /= r.identity_alike_frames;
      r.shape_alike_source_target_mm /= r.identity_alike_frames;
    }
  }

  const size_t n = std::min(target_weights.size(), output_weights.size());
  r.frames = static_cast<int>(n);
  double correlation = 0;
  for (int k = 0; k < model.num_expressions(); ++k) {
    std::vector<double> a, b;
    for (size_t i = 0; i < n; ++i) {
      if (target_weights[i].size() == 0 || output_weights[i].size() == 0) continue;
      a.push_back(target_weights[i][k]);
      b.push_back(output_weights[i][k]);
    }
    if (a.size() < 3) continue;
    double mean = 0, var = 0;
    for (double v : a) mean += v / a.size();
    for (double v : a) var += (v - mean) * (v - mean) / a.size();
    if (std::sqrt(var) < 0.03) continue;  // a weight the target hardly moves says nothing
    correlation += pearson_correlation(a, b);
    ++r.expression_weights_compared;
  }
  r.expression_correlation = r.expression_weights_compared > 0 ? correlation / r.expression_weights_compared : 0;
  return r;
}

}  // namespace facecap
