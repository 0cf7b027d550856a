#include "facecap/swap/expression_ratio.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {

// log of the mean of the channels, kept off log(0).
cv::Mat log_luminance(const cv::Mat& image) {
  cv::Mat grey = image;
  if (image.channels() == 3) cv::transform(image, grey, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
  cv::Mat out;
  cv::log(cv::max(grey, 0.02f), out);
  return out;
}

// Normalised convolution: the weighted Gaussian mean of `value`. A wide
// Gaussian runs on a grid a few times coarser (at most a quarter of sigma
// per coarse texel), then is resampled.
cv::Mat weighted_blur(const cv::Mat& value, const cv::Mat& weight, double sigma, cv::Mat* blurred_weight = nullptr) {
  const int factor = std::max(1, static_cast<int>(sigma / 4.0));
  cv::Mat num = value.mul(weight), den = weight.clone();  // blurred in place below
  if (factor > 1) {
    const cv::Size small((value.cols + factor - 1) / factor, (value.rows + factor - 1) / factor);
    cv::resize(num, num, small, 0, 0, cv::INTER_AREA);
    cv::resize(den, den, small, 0, 0, cv::INTER_AREA);
  }
  const double s = sigma / factor;
  cv::GaussianBlur(num, num, cv::Size(0, 0), s, s, cv::BORDER_CONSTANT);
  cv::GaussianBlur(den, den, cv::Size(0, 0), s, s, cv::BORDER_CONSTANT);
  if (factor > 1) {
    cv::resize(num, num, value.size(), 0, 0, cv::INTER_LINEAR);
    cv::resize(den, den, value.size(), 0, 0, cv::INTER_LINEAR);
  }
  if (blurred_weight) *blurred_weight = den;
  return num / cv::max(den, 1e-6f);
}

}  // namespace

ExpressionRatio::ExpressionRatio(const TriangleMesh& skin, double mm_per_uv, ExpressionRatioOptions options)
    : options_(options), skin_(skin) {
  if (!(mm_per_uv > 0)) throw Error("expression ratio: the mesh has no UV extent");
  if (!(options_.texel_mm > 0 && options_.fine_mm > 0 && options_.coarse_mm > options_.fine_mm))
    throw Error("expression ratio: needs 0 < fine_mm < coarse_mm and a positive texel size");
  const int size = std::clamp(static_cast<int>(std::lround(mm_per_uv / options_.texel_mm)), 32, 1024);
  map_ = rasterize_uv(skin_, size);
  texels_per_mm_ = (size - 1) / mm_per_uv;
}

FaceTexture ExpressionRatio::unshade(const cv::Mat& frame, const Positions& target_points, const PinholeCamera& camera,
                                     const ShCoeffs& lighting,
                                     const std::vector<std::vector<cv::Point>>& excluded) const {
  FaceTexture t = unshade_face(frame, target_points, skin_.triangles, camera, lighting, map_, excluded);
  drop_non_skin(t);
  return t;
}

cv::Mat ExpressionRatio::gains(const FaceTexture& frame) const {
  const int n = map_.size;
  const int channels = options_.colour ? 3 : 1;
  cv::Mat ones(n, n, CV_32FC(channels), cv::Scalar::all(1));
  if (reference_sum_.empty() || frame.empty()) return ones;
  const FaceTexture reference = weighted_mean(reference_sum_);
  // Seen now and in the reference; squarely seen texels count more.
  cv::Mat weight = frame.weight.clone();
  weight.setTo(0, reference.weight <= 0);
  if (cv::countNonZero(weight) < 50) return ones;
  const double fine = options_.fine_mm * texels_per_mm_, coarse = options_.coarse_mm * texels_per_mm_;

  std::vector<cv::Mat> now(3), before(3);
  if (channels == 3) {
    cv::split(frame.albedo, now);
    cv::split(reference.albedo, before);
  } else {
    now[0] = frame.albedo;
    before[0] = reference.albedo;
  }

  // The edge gate, from the reference's log gradient per millimetre: of
  // its luminance, or with `colour` the largest of its channels' (the lips'
  // edge is more one of colour than of brightness).
  cv::Mat seen_reference;
  cv::Mat(reference.weight > 0).convertTo(seen_reference, CV_32F, 1.0 / 255);
  cv::Mat gradient2(n, n, CV_32F, cv::Scalar(0));
  for (int c = 0; c < channels; ++c) {
    const cv::Mat smooth_reference = weighted_blur(log_luminance(before[c]), seen_reference, fine);
    cv::Mat gx, gy;
    cv::Sobel(smooth_reference, gx, CV_32F, 1, 0, 3, texels_per_mm_ / 8.0);
    cv::Sobel(smooth_reference, gy, CV_32F, 0, 1, 3, texels_per_mm_ / 8.0);
    gradient2 = cv::max(gradient2, gx.mul(gx) + gy.mul(gy));
  }
  // Over the fine blur's footprint: the change a sliding edge leaves spreads
  // that far to either side of it.
  const int reach = std::max(1, static_cast<int>(std::lround(2.0 * fine)));
  cv::dilate(gradient2, gradient2,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * reach + 1, 2 * reach + 1)));
  const float edge2 = options_.edge_log_per_mm * options_.edge_log_per_mm;
  cv::Mat r2 = gradient2 / edge2;
  const cv::Mat gate = 1.0f / (1.0f + r2.mul(r2));

  // The change per channel (or in luminance), band-passed: at the fine
  // scale less at the coarse scale, faded where the fine window saw little
  // (the edge of what this frame shows), gated and clamped.
  const float limit = std::log(options_.max_gain);
  std::vector<cv::Mat> out(channels);
  for (int c = 0; c < channels; ++c) {
    const cv::Mat change = log_luminance(now[c]) - log_luminance(before[c]);
    cv::Mat fine_weight;
    const cv::Mat band = weighted_blur(change, weight, fine, &fine_weight) - weighted_blur(change, weight, coarse);
    double max_weight = 0;
    cv::minMaxLoc(fine_weight, nullptr, &max_weight);
    const cv::Mat confidence = fine_weight / (fine_weight + 0.25 * max_weight);
    cv::Mat log_gain = band.mul(confidence).mul(gate);
    cv::min(cv::max(log_gain, -limit), limit, log_gain);
    cv::exp(log_gain, out[c]);
  }
  cv::Mat merged;
  cv::merge(out, merged);
  return merged;
}

}  // namespace facecap
