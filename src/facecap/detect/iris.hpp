#pragma once
// The iris centre of each eye, found inside the eye's six landmarks (iBUG
// 36-41 and 42-47): the dark disc of the iris against the white of the eye.
//
// The eye is resampled to 48 px wide along its own axis, corner to corner
// (the same work at any resolution and roll; an iris seen from the side is
// narrowed along the eye however the face is rolled), its
// outline is shrunk away from the lid line and lashes, and every candidate
// centre and radius is scored by how much of the visible eye's grey-level
// variance a dark disc there on a brighter surround explains (Otsu's
// between-class variance over the visible pixels only, so a lid that covers
// part of the iris neither hides it nor lets a sliver of dark lid win). The
// best score is refined to sub-pixel by a parabola. An eye that is closed,
// too small or shows no dark disc gives nothing.
#include <array>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/detect/landmarks.hpp"

namespace facecap {

struct IrisObservation {
  Vec2d centre = Vec2d::Zero();  // image pixels (pixel centres at integers)
  double radius = 0.0;           // the disc searched for, pixels
  double score = 0.0;            // share of the visible eye's grey-level variance the disc explains
};

struct IrisOptions {
  // Iris radius / eye width (corner to corner), tried in turn: about 0.2 in
  // an average eye (an 11.7 mm iris in a 29 mm eye), more in a narrow one or
  // where the detector marks the corners inside the true ones.
  std::vector<double> radius_shares{0.16, 0.18, 0.2, 0.22, 0.24, 0.26, 0.28, 0.3, 0.32, 0.34};
  // With an expected radius (from a fitted head: the iris's size and its
  // depth), the radii tried are these multiples of it (people's irises vary
  // by about 5 per cent). Where the eye's width is the only guide, a dark eye
  // corner beside an iris turned toward it passes for a larger iris.
  std::vector<double> radius_factors{0.88, 0.94, 1.0, 1.06, 1.12};
  double min_opening = 0.16;    // eyelid opening / eye width below which an eye is closed
  double min_eye_width_px = 9;  // smaller eyes are not searched
  double min_score = 0.4;       // discs that explain less are not an iris
};

// What a fitted head says of how an iris looks in the image (gaze.hpp:
// expected_irises).
struct IrisExpectation {
  double radius_px = 0.0;  // > 0: the iris's radius in the image is about this
  // Width over height of the iris's outline (clamped to [0.3, 1]): a circle
  // seen from the side is an ellipse, narrower across the direction the eye
  // is turned from the camera. On the synthetic renders (`eval track
  // --synthetic 90`, true landmarks, seeds 1-4; heads turned by up to 30
  // degrees), searching for that ellipse instead of a circle took the iris
  // error from 2.10, 1.58, 1.86, 2.27 px to 1.69, 1.21, 1.56, 2.09 and the
  // gaze error from 9.3, 3.1, 2.6, 6.3 to 7.4, 2.2, 2.3, 5.2 degrees; on the
  // nearly frontal real clips the two eyes' directions agree as before.
  double aspect = 1.0;
};

// Eye 0: the subject's right eye (iBUG 36-41, on the image's left for a face
// seen from the front); eye 1: the subject's left (42-47). `grey`: 8-bit.
// `origin`: where grey's first pixel lies in the image the landmarks are in,
// when grey is a crop of it (eye_crop()); what is found is in the image's
// pixels either way, and the same as in the whole image.
std::optional<IrisObservation> locate_iris(const cv::Mat& grey, const Landmarks& landmarks, int eye,
                                           const IrisExpectation& expected = {}, const IrisOptions& options = {},
                                           const cv::Point& origin = {});

// The part of `grey` locate_iris reads for either eye of `landmarks` (with
// a pixel to spare, within the image), for keeping a frame's eyes without
// the frame: searched with its top-left as the origin, it finds what the
// whole image gives (to the last bit for a level eye; a rolled eye's samples
// may round otherwise).
cv::Rect eye_crop(const cv::Size& image, const Landmarks& landmarks);

using IrisPair = std::array<std::optional<IrisObservation>, 2>;

}  // namespace facecap
