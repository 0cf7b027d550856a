#include "facecap/swap/background_warp.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

cv::Mat textured() {
  cv::Mat img(200, 240, CV_8UC3);
  cv::RNG(5).fill(img, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 2);
  return img;
}

std::vector<cv::Point2f> ring(cv::Point2f c, float r, int n) {
  std::vector<cv::Point2f> p;
  for (int i = 0; i < n; ++i) p.emplace_back(c.x + r * std::cos(6.2832f * i / n), c.y + r * std::sin(6.2832f * i / n));
  p.push_back(c);
  return p;
}

// Anchors that fill a disc, as a face's landmarks and outline fill it:
// rings of 24, 16, 10 and 4 points at radii 40, 28, 16 and 6, and the centre.
std::vector<cv::Point2f> disc(cv::Point2f c) {
  std::vector<cv::Point2f> p;
  for (const auto& [r, n] : {std::pair{40.0f, 24}, {28.0f, 16}, {16.0f, 10}, {6.0f, 4}}) {
    auto more = ring(c, r, n);
    p.insert(p.end(), more.begin(), more.end() - 1);
  }
  p.push_back(c);
  return p;
}

const cv::Rect kWindow(40, 20, 160, 160);

// A frame whose pixels hold their own coordinates: a warp's output is its map.
cv::Mat coordinates() {
  cv::Mat frame(200, 240, CV_32FC3);
  for (int y = 0; y < frame.rows; ++y)
    for (int x = 0; x < frame.cols; ++x) frame.at<cv::Vec3f>(y, x) = cv::Vec3f(float(x), float(y), 0);
  return frame;
}

// The map of a warp moving the anchors `from` to `to` in the window
// (40, 20, 160 x 160): the output of warping coordinates().
cv::Mat warp_map(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to) {
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(coordinates(), from, to, kWindow, out);
  return out;
}

}  // namespace

TEST(BackgroundWarp, UnmovedAnchorsLeaveTheFrame) {
  const cv::Mat frame = textured();
  const auto anchors = ring({120, 100}, 40, 12);
  const cv::Rect window(40, 20, 160, 160);
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, anchors, anchors, window, out);
  EXPECT_GT(warp.control_count(), 12);
  cv::Mat d;
  cv::absdiff(out, frame(window), d);
  double worst = 0;
  cv::minMaxLoc(d.reshape(1), nullptr, &worst);
  EXPECT_LE(worst, 1.0);
}

TEST(BackgroundWarp, AnchorsCarryTheirSurroundingsAndTheBorderStays) {
  const cv::Mat frame = textured();
  const auto from = disc({120, 100});
  std::vector<cv::Point2f> to = from;
  for (auto& p : to) p += cv::Point2f(6, 0);  // the face moved 6 px right
  const cv::Rect window(40, 20, 160, 160);
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, from, to, window, out);
  // Inside the ring the content moved by 6 px: out(x + 6) == frame(x).
  for (int y = 90; y <= 110; y += 5) {
    for (int x = 110; x <= 130; x += 5) {
      const cv::Vec3b a = out.at<cv::Vec3b>(y - window.y, x + 6 - window.x), b = frame.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 2) << x << "," << y;
    }
  }
  // The window's border does not move.
  EXPECT_EQ(out.at<cv::Vec3b>(0, 0), frame.at<cv::Vec3b>(window.y, window.x));
  EXPECT_EQ(out.at<cv::Vec3b>(159, 159), frame.at<cv::Vec3b>(window.y + 159, window.x + 159));
}

// Beyond the fixed ring the background is untouched: the warp fades out
// around the face instead of bending everything up to the window's edge.
TEST(BackgroundWarp, TheBackgroundBeyondTheRingStaysPut) {
  const cv::Mat frame = textured();
  const auto from = ring({120, 100}, 30, 12);
  std::vector<cv::Point2f> to = from;
  for (auto& p : to) p += cv::Point2f(6, 0);
  const cv::Rect window(20, 10, 200, 180);
  const auto fixed = fixed_ring(from, to, window);
  ASSERT_EQ(static_cast<int>(fixed.size()), kRingPoints);
  for (const cv::Point2f& p : fixed) {
    EXPECT_TRUE(window.contains(cv::Point(int(p.x), int(p.y))));
    EXPECT_GT(cv::norm(p - cv::Point2f(120, 100)), 36.0);  // outside both anchor sets
  }
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, from, to, window, out);
  // Points between the ring (radius about 47) and the window's border.
  for (const cv::Point p :
       {cv::Point(30, 20), cv::Point(60, 40), cv::Point(200, 170), cv::Point(30, 150), cv::Point(190, 30)}) {
    EXPECT_EQ(out.at<cv::Vec3b>(p.y - window.y, p.x - window.x), frame.at<cv::Vec3b>(p)) << p;
  }
}

// An anchor moved past its neighbours (a new face's point crossing the
// target's outline) must not tear the map: a triangle laid out on the
// target's points turns over in the destination, overlaps its neighbours
// and leaves pixels that keep the unwarped frame. The frame holds each
// pixel's own coordinates, so the output is the map itself.
TEST(BackgroundWarp, AnAnchorMovedPastItsNeighboursLeavesNoTear) {
  const auto from = ring({120, 100}, 40, 12);  // the centre is the last point
  std::vector<cv::Point2f> to = from;
  to.back() = {172, 104};  // past the ring's point at (160, 100)
  const cv::Mat out = warp_map(from, to);
  // Neighbouring pixels sample the frame at most a few pixels apart (the
  // warp stretches nothing more than 40 px of source over 12 px), where a
  // tear puts an unwarped pixel next to one carried 50 px.
  double worst = 0;
  for (int y = 0; y + 1 < out.rows; ++y) {
    for (int x = 0; x + 1 < out.cols; ++x) {
      const cv::Vec3f p = out.at<cv::Vec3f>(y, x);
      for (const cv::Vec3f& q : {out.at<cv::Vec3f>(y, x + 1), out.at<cv::Vec3f>(y + 1, x)})
        worst = std::max(worst, double(cv::norm(p - q)));
    }
  }
  EXPECT_LT(worst, 8.0);
  // The moved anchor carries the frame's centre with it.
  const cv::Vec3f at_anchor = out.at<cv::Vec3f>(104 - kWindow.y, 172 - kWindow.x);
  EXPECT_NEAR(at_anchor[0], 120.0f, 1.0f);
  EXPECT_NEAR(at_anchor[1], 100.0f, 1.0f);
}

// Anchors turned away from the camera in either face are left out; those
// without a normal (past the skin mesh) are kept.
TEST(BackgroundWarp, AnchorsTurnedAwayInEitherFaceAreLeftOut) {
  // Camera space, the camera at the origin looking down +z.
  Positions target(3, 4), swapped(3, 4), target_normals(3, 4), swapped_normals(3, 4);
  target << 0, 1, 2, 0,  //
      0, 0, 0, 0,        //
      50, 52, 50, 50;
  swapped = target;
  target_normals << 0, 0, 0, 0,  //
      0, 0, 0, 0,                //
      -1, 1, -1, -1;             // vertex 1 faces away from the camera
  swapped_normals = target_normals;
  swapped_normals.col(2) = Vec3f(0, 0, 1);  // vertex 2 turns away in the new face only
  const std::vector<bool> shown =
      anchors_facing({0, 1, 2, 7}, target, target_normals, swapped, swapped_normals, /*skin_vertices=*/4);
  EXPECT_EQ(shown, (std::vector<bool>{true, false, false, true}));
  // A grazing normal that still faces the camera is kept.
  target_normals.col(0) = Vec3f(0.999f, 0, -0.045f);
  swapped_normals.col(0) = target_normals.col(0);
  EXPECT_TRUE(anchors_facing({0}, target, target_normals, swapped, swapped_normals, 4)[0]);
}

// An anchor outside the window (a face cut off by the frame's edge) does
// not drag the window's border, which holds still.
TEST(BackgroundWarp, AnAnchorOutsideTheWindowIsLeftOut) {
  const cv::Mat frame = textured();
  auto from = ring({120, 100}, 40, 12);
  auto to = from;
  from.emplace_back(80, 5);  // above the window's top edge (y = 20)
  to.emplace_back(84, 2);
  const cv::Rect window(40, 20, 160, 160);
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(frame, from, to, window, out);
  for (int x = 60; x <= 100; x += 10)
    EXPECT_EQ(out.at<cv::Vec3b>(0, x - window.x), frame.at<cv::Vec3b>(window.y, x)) << x;
}

// The disc's anchors with its left half narrowed by a fifth, as a narrower
// new face's; with `scatter`, its outline's 24 points land up to 3 px apart
// from where that puts them.
std::vector<cv::Point2f> narrowed(const std::vector<cv::Point2f>& disc_points, cv::Point2f centre, bool scatter) {
  std::vector<cv::Point2f> to = disc_points;
  for (cv::Point2f& p : to)
    if (p.x < centre.x) p.x = centre.x + 0.8f * (p.x - centre.x);
  if (scatter)
    for (int k = 0; k < 24; ++k) to[k] += cv::Point2f(k % 2 ? 3.0f : -3.0f, 2.0f * float(k % 3 - 1));
  return to;
}

TEST(BackgroundWarp, EachAnchorCarriesItsOwnPixel) {
  const cv::Point2f centre(120, 100);
  const auto from = disc(centre);
  const auto to = narrowed(from, centre, false);
  const cv::Mat out = warp_map(from, to);
  for (size_t k = 0; k < to.size(); ++k) {
    cv::Mat sampled;
    cv::getRectSubPix(out, cv::Size(1, 1), to[k] - cv::Point2f(kWindow.tl()), sampled);
    const cv::Vec3f s = sampled.at<cv::Vec3f>(0, 0);
    EXPECT_LT(cv::norm(cv::Point2f(s[0], s[1]) - from[k]), 0.1) << k;
  }
}

// Where neighbouring anchors move differently (the outline's points
// scattered), the map between the outline and the ring bends smoothly: an
// affine map per triangle creased along every edge of the slivers fanning
// out to the ring, and hair crossing them bent into zigzags. Beyond the
// outline, the map's second difference from pixel to pixel stays under
// 1.5 px, where the triangles gave 3.6.
TEST(BackgroundWarp, TheMapBeyondTheOutlineHasNoCreases) {
  const cv::Point2f centre(120, 100);
  const auto from = disc(centre);
  const cv::Mat out = warp_map(from, narrowed(from, centre, true));
  double worst = 0;
  for (int y = 1; y + 1 < out.rows; ++y) {
    for (int x = 1; x + 1 < out.cols; ++x) {
      if (cv::norm(cv::Point2f(float(x + kWindow.x), float(y + kWindow.y)) - centre) < 42) continue;
      const cv::Vec3f m = out.at<cv::Vec3f>(y, x);
      const cv::Vec3f across = out.at<cv::Vec3f>(y, x - 1) + out.at<cv::Vec3f>(y, x + 1) - 2 * m;
      const cv::Vec3f down = out.at<cv::Vec3f>(y - 1, x) + out.at<cv::Vec3f>(y + 1, x) - 2 * m;
      for (int c = 0; c < 2; ++c) worst = std::max({worst, double(std::abs(across[c])), double(std::abs(down[c]))});
    }
  }
  EXPECT_LT(worst, 1.5);
}

// Around a feature (an eye, the mouth) the triangles' map holds: what lies
// between its points moves with them as the face's mesh edges do, where the
// spline bends between sparse anchors (12 on a circle moved by 6 px: up to
// 1.6 px off a translation 10 px from the centre).
TEST(BackgroundWarp, AroundAFeatureTheTrianglesMapHolds) {
  const auto from = ring({120, 100}, 40, 12);
  std::vector<cv::Point2f> to = from;
  for (auto& p : to) p += cv::Point2f(6, 0);
  const std::vector<cv::Point2f> outline(to.begin(), to.end() - 1);  // the circle, without its centre
  BackgroundWarp warp;
  cv::Mat out;
  warp.warp(coordinates(), from, to, kWindow, out, {outline});
  double worst = 0;
  for (int y = 75; y <= 125; ++y) {
    for (int x = 101; x <= 151; ++x) {  // within 25 px of the moved centre (126, 100)
      if (cv::norm(cv::Point2f(float(x), float(y)) - cv::Point2f(126, 100)) > 25) continue;
      const cv::Vec3f p = out.at<cv::Vec3f>(y - kWindow.y, x - kWindow.x);
      worst = std::max(worst, double(cv::norm(cv::Point2f(p[0] - (x - 6), p[1] - y))));
    }
  }
  EXPECT_LT(worst, 0.05);
  // Without the feature, the spline alone.
  const cv::Mat spline = warp_map(from, to);
  const cv::Vec3f p = spline.at<cv::Vec3f>(100 - kWindow.y, 136 - kWindow.x);
  EXPECT_GT(cv::norm(cv::Point2f(p[0] - 130, p[1] - 100)), 0.3);
}

// Anchors all on one point put the rings there too, which leaves the spline
// nothing to fit: the window is left as it was, with no NaN in it.
TEST(BackgroundWarp, AnchorsInOnePlaceLeaveTheFrame) {
  const std::vector<cv::Point2f> from(5, cv::Point2f(120, 100));
  const cv::Mat out = warp_map(from, from);
  ASSERT_EQ(out.size(), kWindow.size());
  cv::Mat d;
  cv::absdiff(out, coordinates()(kWindow), d);
  double worst = 0;
  cv::minMaxLoc(d.reshape(1), nullptr, &worst);
  EXPECT_EQ(worst, 0.0);
}

}  // namespace facecap
