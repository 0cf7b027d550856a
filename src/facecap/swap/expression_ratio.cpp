#include "facecap/swap/expression_ratio.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"
#include "facecap/swap/weighted_channels.hpp"
#include "facecap/swap/wide_blur.hpp"

namespace facecap {

namespace {

// log of the colour (or with one channel wanted, of the mean of the
// three), kept off log(0).
cv::Mat log_colour(const cv::Mat& bgr, int channels) {
  cv::Mat c = bgr;
  if (channels == 1) cv::transform(bgr, c, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
  cv::Mat out;
  cv::log(cv::max(c, 0.02f), out);
  return out;
}

// A Gaussian blur with zeros outside the texture.
cv::Mat blur(const cv::Mat& image, double sigma) { return wide_blur(image, sigma, cv::BORDER_CONSTANT); }

// Normalised convolution, the weighted Gaussian mean of a value, from the
// value times its weight (times_weight) and the weight, blurred alike.
cv::Mat normalised_blur(const cv::Mat& weighted_value, const cv::Mat& blurred_weight, double sigma) {
  cv::Mat out = blur(weighted_value, sigma);
  divide_by_weight(out, blurred_weight, 1e-6f);
  return out;
}

}  // namespace

ExpressionRatio::ExpressionRatio(const TriangleMesh& skin, double mm_per_uv, ExpressionRatioOptions options)
    : options_(options), skin_(skin) {
  if (!(mm_per_uv > 0)) throw Error("expression ratio: the mesh has no UV extent");
  if (!(options_.texel_mm > 0 && options_.fine_mm > 0 && options_.coarse_mm > options_.fine_mm))
    throw Error("expression ratio: needs 0 < fine_mm < coarse_mm and a positive texel size");
  grid_ = millimetre_grid(skin_, mm_per_uv, options_.texel_mm);
}

FaceTexture ExpressionRatio::unshade(const cv::Mat& frame, const Positions& target_points, const PinholeCamera& camera,
                                     const ShCoeffs& lighting,
                                     const std::vector<std::vector<cv::Point>>& excluded) const {
  FaceTexture t = unshade_face(frame, target_points, skin_.triangles, camera, lighting, grid_.map, excluded);
  drop_non_skin(t);
  return t;
}

void ExpressionRatio::clear_reference() {
  reference_sum_ = FaceTexture();
  log_reference_ = seen_reference_ = gate_ = cv::Mat();
}

void ExpressionRatio::add_reference(const FaceTexture& texture) {
  accumulate(reference_sum_, texture);
  const FaceTexture reference = weighted_mean(reference_sum_);
  const int channels = options_.colour ? 3 : 1;
  const double fine = options_.fine_mm * grid_.texels_per_mm;
  log_reference_ = log_colour(reference.albedo, channels);
  cv::Mat(reference.weight > 0).convertTo(seen_reference_, CV_32F, 1.0 / 255);

  // The edge gate, from the reference's log gradient per millimetre: of
  // its luminance, or with `colour` the largest of its channels' (the lips'
  // edge is more one of colour than of brightness).
  const cv::Mat smooth =
      normalised_blur(times_weight(log_reference_, seen_reference_), blur(seen_reference_, fine), fine);
  cv::Mat gx, gy;
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3, grid_.texels_per_mm / 8.0);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3, grid_.texels_per_mm / 8.0);
  std::vector<cv::Mat> per_channel;
  cv::split(gx.mul(gx) + gy.mul(gy), per_channel);
  cv::Mat gradient2 = per_channel[0];
  for (int c = 1; c < channels; ++c) gradient2 = cv::max(gradient2, per_channel[c]);
  // Over the fine blur's footprint: the change a sliding edge leaves spreads
  // that far to either side of it.
  const int reach = std::max(1, static_cast<int>(std::lround(2.0 * fine)));
  cv::dilate(gradient2, gradient2,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * reach + 1, 2 * reach + 1)));
  const cv::Mat r2 = gradient2 / (options_.edge_log_per_mm * options_.edge_log_per_mm);
  gate_ = 1.0f / (1.0f + r2.mul(r2));
}

cv::Mat ExpressionRatio::gains(const FaceTexture& frame) const {
  const int n = grid_.map.size;
  const int channels = options_.colour ? 3 : 1;
  cv::Mat ones(n, n, CV_32FC(channels), cv::Scalar::all(1));
  if (reference_sum_.empty() || frame.empty()) return ones;
  // Seen now and in the reference; squarely seen texels count more.
  cv::Mat weight = frame.weight.clone();
  weight.setTo(0, seen_reference_ <= 0);
  if (cv::countNonZero(weight) < 50) return ones;
  const double fine = options_.fine_mm * grid_.texels_per_mm, coarse = options_.coarse_mm * grid_.texels_per_mm;

  // The change, band-passed (at the fine scale less at the coarse scale),
  // faded where the fine window saw little (the edge of what this frame
  // shows), gated and clamped.
  const cv::Mat weighted_change = times_weight(log_colour(frame.albedo, channels) - log_reference_, weight);
  const cv::Mat fine_weight = blur(weight, fine);
  const cv::Mat band = normalised_blur(weighted_change, fine_weight, fine) -
                       normalised_blur(weighted_change, blur(weight, coarse), coarse);
  double max_weight = 0;
  cv::minMaxLoc(fine_weight, nullptr, &max_weight);
  const cv::Mat confidence = fine_weight / (fine_weight + 0.25 * max_weight);
  cv::Mat log_gain = times_weight(band, confidence.mul(gate_));
  const float limit = std::log(options_.max_gain);
  cv::min(cv::max(log_gain, -limit), limit, log_gain);
  cv::Mat out;
  cv::exp(log_gain, out);
  return out;
}

}  // namespace facecap
