#pragma once
// `facecap eval swap`: what chapter 6 promises, measured.
//  - Self-swap (--self VIDEO, Fig. 6.7): the first frame is the source photo
//    and the rest of the video the target, so the truth is the video itself:
//    photometric error (0-255, mean over RGB) over the pixels the new face
//    covers (alpha > 0.5), median and mean over all frames but the first.
//  - Source into target: the output, tracked again, should carry the
//    source's identity and the target's expression; the blend boundary
//    should not stand out (seam_ratio: mean gradient magnitude on the outer
//    edge of the blend over that in a band just inside it).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "facecap/pipeline/swap_job.hpp"

namespace facecap {

struct SwapSelfEval {
  int frames = 0;              // target frames measured (all but the first)
  int source_frames_used = 0;  // source frames the identity was solved from
  double photometric_median = 0;
  double photometric_mean = 0;
  double face_pixels_per_frame = 0;
  // The mean split by where the error lies: boxes around the detected mouth
  // and around the eyes with their brows, and the rest of the face; share:
  // that region's part of the face pixels.
  struct Region {
    double mean = 0, share = 0;
  };
  std::array<Region, 3> regions;  // mouth, eyes, rest
  // SwappedFrame::covered, mean and largest over the frames measured: on
  // footage where nothing covers the face, how much of it the occlusion
  // mask takes for a cover (those pixels are the target's, and are left out
  // of the photometric error, which alpha > 0.5 selects).
  double covered_mean = 0, covered_max = 0;
  SwapJobTimings timings;
};

// The video's first frame is the source photo (source_frames > 1: its first
// frames, as a folder of photos) and the whole video the target.
SwapSelfEval evaluate_swap_self(const FaceModel& model, const std::string& video, const SwapJobOptions& options,
                                int source_frames = 1);

struct SwapPairEval {
  int frames = 0;
  double identity_distance_output_source = 0;  // |alpha_out - alpha_S|
  double identity_distance_output_target = 0;  // |alpha_out - alpha_T|
  double identity_distance_source_target = 0;  // |alpha_S - alpha_T|
  // The same three with every image fitted alike, each frame as a photo
  // (frames 5, 15, ... of the output and of the target, at most
  // kAlikeIdentityFrames of them), averaged: a video's identity comes from 30
  // frames of one pose and lighting, the photo's from one, and images taken
  // alike land near each other whoever they show (the output and its target:
  // same video, pose and expression). 0 with identity_alike_frames 0.
  double identity_alike_output_source = 0;
  double identity_alike_output_target = 0;
  double identity_alike_source_target = 0;
  int identity_alike_frames = 0;
  // The alike fits' neutral face regions against each other after a
  // similarity alignment, mean vertex distance in mm: the shapes alone. The
  // identity distances also count the face's size, which a photo does not fix
  // and the swap takes from the target (SwapOptions::match_target_size).
  double shape_alike_output_source_mm = 0;
  double shape_alike_output_target_mm = 0;
  double shape_alike_source_target_mm = 0;
  double expression_correlation = 0;  // mean over the weights the target moves of corr(out, target)
  int expression_weights_compared = 0;
  double seam_ratio = 0;  // mean over frames
  // The same measure on the untouched target frames: the face's outline
  // often lies on real edges (jaw, hairline), which no blend should remove.
  double seam_ratio_target = 0;
  int faces_in_source = 0;
  double covered_mean = 0, covered_max = 0;  // SwappedFrame::covered over the frames swapped
  // hue_beyond_target per frame, averaged over the frames swapped.
  double hue_beyond_cool = 0, hue_beyond_warm = 0;
  SwapJobTimings timings;
};

inline constexpr int kAlikeIdentityFrames = 6;

SwapPairEval evaluate_swap_pair(const FaceModel& model, const std::string& photo, const std::string& video,
                                const SwapJobOptions& options, const std::filesystem::path& output = {});

// Seam measure of one blended frame: mean gradient magnitude of `image` on
// the outer edge of `alpha` (> 0.01, holes filled: the eyes and mouth of the
// target show through the face mesh by design) over that 6-10 px inside it;
// 0 when either is empty.
double seam_ratio(const cv::Mat& image, const cv::Mat& alpha);

// Colours the new face shows that the target's face does not: over the
// pixels where `alpha` > 0.5, the opponent colours of `target` relative to
// each pixel's level ((B - R) / Y, (2G - R - B) / Y, Y the mean of B, G, R)
// span a box (their 0.5th to 99.5th percentiles, widened by 0.05); the
// shares of `output`'s face pixels beyond it toward blue or green (cool) and
// toward red or magenta (warm). Pixels with Y under 16 have no hue to speak
// of and count as neither. A graded video (sepia, desaturated) spans a narrow
// box, and a colour transfer that shifts hue shows at once, whether the
// pixel is a bright cheek or a dark brow. Zeros when fewer than 100 target
// pixels count.
struct HueBeyond {
  double cool = 0, warm = 0;
};
HueBeyond hue_beyond_target(const cv::Mat& output, const cv::Mat& target, const cv::Mat& alpha);

}  // namespace facecap
