#pragma once
// Footage with something put in front of the face, for the tests of what
// an edit leaves in front of it (swap and transform).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"

namespace facecap {

// Per pixel, the largest difference over the channels of two BGR images
// (CV_8U).
inline cv::Mat largest_channel_difference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat difference, channels[3];
  cv::absdiff(a, b, difference);
  cv::split(difference, channels);
  return cv::max(cv::max(channels[0], channels[1]), channels[2]);
}

// The first `frames` frames of `video`, a filled disc of `colour` and
// `radius` at centre(i) painted over frame i from `cover_from` on: written
// into `folder` as frame_NNN.png (an image-folder input) and returned.
inline std::vector<cv::Mat> write_covered_frames(const std::filesystem::path& video,
                                                 const std::filesystem::path& folder, int frames, int cover_from,
                                                 const std::function<cv::Point(int)>& centre, int radius,
                                                 const cv::Scalar& colour) {
  std::vector<cv::Mat> images;
  auto source = open_input(video.string());
  Frame f;
  std::filesystem::create_directories(folder);
  for (int i = 0; i < frames && source->read(f); ++i) {
    cv::Mat image = f.image.clone();
    if (i >= cover_from) cv::circle(image, centre(i), radius, colour, cv::FILLED);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%03d.png", i);
    write_image((folder / name).string(), image);
    images.push_back(image);
  }
  return images;
}

// A hand of the face's own skin colour (the cheek's median in the first
// frame of address_720p_a, rounded and grainy as skin is) comes up over the
// mouth and chin from below (frames 20-27, about 15 mm a frame), rests
// there for a second with a slight tremor (frames 28-51) and goes down again
// (52-59): no colour tells it from the face, only its motion across it
// (MovingCover).
namespace skin_coloured_hand {

constexpr int kFrames = 72, kEnter = 20, kRest = 28, kLeave = 52, kGone = 60;

// The palm's centre: rests below the chin, the fingers up over the mouth.
inline cv::Point2f palm(int i) {
  const cv::Point2f rest(530, 480);
  if (i < kEnter || i >= kGone) return cv::Point2f(rest.x, 2000);
  if (i < kRest) return cv::Point2f(rest.x, rest.y + 25.0f * (kRest - i));
  if (i < kLeave) return cv::Point2f(rest.x + 2.0f * std::sin(0.9f * i), rest.y + 1.5f * std::cos(1.3f * i));
  return cv::Point2f(rest.x, rest.y + 25.0f * (i - kLeave + 1));
}

inline cv::Mat hand_mask(cv::Size size, int i) {
  cv::Mat mask(size, CV_8U, cv::Scalar(0));
  const cv::Point2f c = palm(i);
  cv::ellipse(mask, c, cv::Size(68, 80), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  const float offsets[4] = {-48, -16, 16, 48}, lengths[4] = {105, 125, 120, 100};
  for (int f = 0; f < 4; ++f)
    cv::line(mask, cv::Point2f(c.x + offsets[f], c.y - 40), cv::Point2f(c.x + offsets[f] * 1.1f, c.y - 40 - lengths[f]),
             cv::Scalar(255), 28);
  return mask;
}

struct HandFrames {
  std::vector<cv::Mat> input;  // the frames with the hand
  std::vector<cv::Mat> hands;  // each frame's hand, less 4 px at its edge (8-bit)
};

// The first kFrames frames of `video` (address_720p_a) with the hand over
// them, written into `folder` as frame_NNN.png and returned.
inline HandFrames write_hand_frames(const std::filesystem::path& video, const std::filesystem::path& folder) {
  HandFrames out;
  auto source = open_input(video.string());
  Frame f;
  std::filesystem::create_directories(folder);
  cv::Scalar skin;
  cv::Mat grain;
  for (int i = 0; i < kFrames && source->read(f); ++i) {
    if (i == 0) {
      // The cheek's median colour, per channel.
      std::vector<cv::Mat> channels;
      cv::split(f.image(cv::Rect(420, 280, 30, 30)), channels);
      for (int k = 0; k < 3; ++k) {
        std::vector<uchar> v(channels[k].begin<uchar>(), channels[k].end<uchar>());
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        skin[k] = v[v.size() / 2];
      }
      // The skin's grain, moving with the hand.
      grain = cv::Mat(512, 512, CV_32F);
      cv::RNG(11).fill(grain, cv::RNG::NORMAL, 0.0, 8.0);
      cv::GaussianBlur(grain, grain, cv::Size(0, 0), 1.5);
    }
    const cv::Mat mask = hand_mask(f.image.size(), i);
    // Rounded as fingers are: darker toward their edges.
    cv::Mat inside;
    cv::distanceTransform(mask, inside, cv::DIST_L2, 3);
    cv::Mat soft;
    mask.convertTo(soft, CV_32F, 1.0 / 255);
    cv::GaussianBlur(soft, soft, cv::Size(0, 0), 1.0);
    cv::Mat image = f.image.clone();
    const cv::Point2f c = palm(i);
    const float top = c.y - 170, height = 250;
    for (int y = 0; y < image.rows; ++y) {
      const float lengthwise = 0.92f + 0.16f * std::clamp((y - top) / height, 0.0f, 1.0f);
      for (int x = 0; x < image.cols; ++x) {
        const float a = soft.at<float>(y, x);
        if (a <= 0) continue;
        const float shade = lengthwise * (0.8f + 0.2f * std::min(1.0f, inside.at<float>(y, x) / 12.0f));
        cv::Vec3b& p = image.at<cv::Vec3b>(y, x);
        const float g = grain.at<float>(std::clamp(y - int(c.y) + 256, 0, 511), std::clamp(x - int(c.x) + 256, 0, 511));
        for (int k = 0; k < 3; ++k) p[k] = cv::saturate_cast<uchar>((1 - a) * p[k] + a * (skin[k] * shade + g));
      }
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%03d.png", i);
    write_image((folder / name).string(), image);
    out.input.push_back(image);
    cv::Mat inner;
    cv::erode(mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(9, 9)));
    out.hands.push_back(inner);
  }
  return out;
}

}  // namespace skin_coloured_hand

}  // namespace facecap
