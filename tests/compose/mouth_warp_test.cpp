#include "facecap/compose/mouth_warp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace facecap {

namespace {

// `points` rounded to pixels, relative to `origin`.
std::vector<cv::Point> polygon(const std::vector<cv::Point2f>& points, cv::Point origin = {}) {
  std::vector<cv::Point> out;
  for (const cv::Point2f& p : points) out.emplace_back(cvRound(p.x - origin.x), cvRound(p.y - origin.y));
  return out;
}

// 255 inside `outline` in the window `box` of the frame.
cv::Mat inside(const std::vector<cv::Point2f>& outline, const cv::Rect& box) {
  cv::Mat m(box.size(), CV_8U, cv::Scalar(0));
  cv::fillPoly(m, std::vector<std::vector<cv::Point>>{polygon(outline, box.tl())}, cv::Scalar(255));
  return m;
}

// `points` with those above `centre_y` (the upper lid's) moved down by `dy`
// at the top (negative: up), in proportion to their height above it
// (`half_height` at the top): most at the top, none at the corners.
std::vector<cv::Point2f> upper_lid_moved(std::vector<cv::Point2f> points, float dy, float centre_y, float half_height) {
  for (cv::Point2f& p : points)
    if (p.y < centre_y - 0.5f) p.y += dy * (centre_y - p.y) / half_height;
  return points;
}

// The layer a re-render leaves around `content`: the lids drawn (skin
// colour, mask set) outside the `opening`, the frame's pixels (mask unset)
// inside it.
FaceLayer rerendered_lids(const cv::Mat& frame, const cv::Rect& content, const std::vector<cv::Point2f>& opening) {
  FaceLayer layer = make_layer(frame, content, 8);
  layer.mask.setTo(255);
  layer.mask.setTo(0, inside(opening, layer.box));
  layer.colour.setTo(cv::Scalar(60, 90, 160), layer.mask);
  return layer;
}

// An eye seen in a 160 x 120 frame: lid-coloured skin, and an opening
// (a lens 60 px wide, 16 tall, centred at (80, 60)) of white with a dark
// iris 14 px across at its centre.
struct Eye {
  cv::Mat frame = cv::Mat(120, 160, CV_8UC3, cv::Scalar(60, 90, 160));
  std::vector<cv::Point2f> contour;  // 16 points, clockwise from the inner corner
  Eye() {
    for (int i = 0; i < 16; ++i) {
      const double a = 2 * M_PI * i / 16;
      contour.emplace_back(float(80 - 30 * std::cos(a)), float(60 - 8 * std::sin(a)));
    }
    cv::fillPoly(frame, std::vector<std::vector<cv::Point>>{polygon(contour)}, cv::Scalar(235, 235, 235), cv::LINE_AA);
    cv::circle(frame, {80, 60}, 7, cv::Scalar(40, 50, 60), cv::FILLED, cv::LINE_AA);
  }
  // The contour with the upper lid's points moved down by `dy` (negative: up).
  std::vector<cv::Point2f> upper_lid_moved(float dy) const { return facecap::upper_lid_moved(contour, dy, 60, 8); }
  // The layer a re-render leaves with the lids drawn outside `opening`.
  FaceLayer rerendered(const std::vector<cv::Point2f>& opening) const {
    return rerendered_lids(frame, cv::Rect(40, 30, 80, 60), opening);
  }
};

// An eye as a face shows it, in a 320 x 240 frame: the opening 120 px wide
// and 32 tall, centred at (160, 120); the skin's loop (`contour`) 4 px
// outside the lids' edges, where the lid hides it; an iris 56 px across
// (0.23 of the eye's width in radius) that both lids cut, with a pupil and
// a catchlight; the lids' edges dark (lashes). `visible`: the opening the
// landmarks mark.
struct RealEye {
  static constexpr float kIrisRadius = 28.0f;
  cv::Mat frame = cv::Mat(240, 320, CV_8UC3, cv::Scalar(60, 90, 160));
  std::vector<cv::Point2f> contour, visible;
  RealEye() {
    for (int i = 0; i < 24; ++i) {
      const double a = 2 * M_PI * i / 24;
      contour.emplace_back(float(160 - 60 * std::cos(a)), float(120 - 20 * std::sin(a)));
      visible.emplace_back(float(160 - 60 * std::cos(a)), float(120 - 16 * std::sin(a)));
    }
    cv::Mat eyeball(frame.size(), CV_8UC3, cv::Scalar(235, 235, 235));
    cv::circle(eyeball, {160, 120}, int(kIrisRadius), cv::Scalar(40, 60, 90), cv::FILLED, cv::LINE_AA);
    cv::circle(eyeball, {160, 120}, 8, cv::Scalar(10, 10, 10), cv::FILLED, cv::LINE_AA);
    cv::circle(eyeball, {166, 126}, 2, cv::Scalar(250, 250, 250), cv::FILLED, cv::LINE_AA);
    eyeball.copyTo(frame, inside(visible, cv::Rect({}, frame.size())));
    cv::polylines(frame, std::vector<std::vector<cv::Point>>{polygon(visible)}, true, cv::Scalar(20, 25, 30), 2,
                  cv::LINE_AA);
  }
};

// RealEye's upper lid raised by 20 px (its edge from 16 px above the
// centre to 36, above the iris's top at 28) and the eye widened into the
// layer the re-render leaves (the lids drawn outside the new loop).
struct RaisedLid {
  RealEye eye;
  std::vector<cv::Point2f> wider = upper_lid_moved(eye.contour, -25, 120, 20);
  std::vector<cv::Point2f> lid_edge = upper_lid_moved(eye.visible, -20, 120, 16);
  cv::Rect content{80, 80, 160, 80};
  cv::Rect box = make_layer(eye.frame, content, 8).box;
  VisibleEye visible{{160, 120}, RealEye::kIrisRadius, eye.visible};

  // The inside of `outline` in the layer's window.
  cv::Mat inside(const std::vector<cv::Point2f>& outline) const { return facecap::inside(outline, box); }
  // The layer's grey levels after widen_opening, with or without what the frame shows of the eye.
  cv::Mat widened(const VisibleEye* shown) const {
    FaceLayer layer = rerendered_lids(eye.frame, content, wider);
    widen_opening(eye.frame, eye.contour, wider, layer, shown);
    cv::Mat grey;
    cv::cvtColor(layer.colour, grey, cv::COLOR_BGR2GRAY);
    return grey;
  }
};

}  // namespace

TEST(MouthWarp, AnUnmovedContourCopiesTheMouth) {
  cv::Mat frame(120, 160, CV_8UC3);
  cv::RNG(9).fill(frame, cv::RNG::UNIFORM, 0, 255);
  const std::vector<cv::Point2f> contour = {{60, 60}, {80, 52}, {100, 60}, {80, 70}};
  FaceLayer layer = make_layer(frame, cv::Rect(50, 45, 60, 35), 8);
  layer.colour.setTo(cv::Scalar(0, 0, 0));
  warp_mouth(frame, contour, contour, layer);
  ASSERT_GT(cv::countNonZero(layer.mask), 200);
  cv::Mat d;
  cv::absdiff(layer.colour, frame(layer.box), d);
  cv::Mat inside;
  cv::erode(layer.mask, inside, cv::Mat(), {-1, -1}, 2);  // away from the edge's interpolation
  EXPECT_LE(cv::mean(d, inside)[0], 1.0);
}

// A closed mouth, its lips under a pixel apart as tracked, moved by a
// fraction of a pixel: the fan's triangles are slivers, and the pixels their
// smoothed fill paints lie off them. Those come from the seam between the
// lips too, not from the sliver's affine map carried far across the lips
// (talking_webcam2 --to anger, frame 60: white flecks on the seam, 60 -> 164;
// the contours below are that frame's, moved).
TEST(MouthWarp, AClosedMouthPaintsItsSeamNotWhatLiesAcrossTheLips) {
  cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(220, 220, 220));
  frame.rowRange(57, 64).setTo(cv::Scalar(40, 40, 40));  // the seam, 3 px each way
  const std::vector<cv::Point2f> from = {{60.21f, 61.49f}, {69.30f, 59.68f}, {75.04f, 60.47f}, {80.65f, 59.98f},
                                         {89.21f, 62.05f}, {81.31f, 60.54f}, {75.32f, 60.86f}, {69.28f, 60.39f}};
  const std::vector<cv::Point2f> to = {{60.82f, 61.37f}, {69.64f, 59.70f}, {75.04f, 60.46f}, {80.39f, 59.63f},
                                       {88.50f, 61.45f}, {81.11f, 60.17f}, {75.32f, 60.86f}, {69.49f, 60.07f}};
  FaceLayer layer = make_layer(frame, cv::Rect(50, 45, 60, 35), 8);
  layer.mask.setTo(0);
  warp_mouth(frame, from, to, layer);
  ASSERT_GT(cv::countNonZero(layer.mask), 20);
  cv::Mat grey;
  cv::cvtColor(layer.colour, grey, cv::COLOR_BGR2GRAY);
  double brightest = 0;
  cv::minMaxLoc(grey, nullptr, &brightest, nullptr, nullptr, layer.mask);
  EXPECT_LE(brightest, 41.0);
}

// A contour without area (its points on one row, as a shut mouth's may be)
// has no triangle to map a pixel through: the layer is left as it was.
TEST(MouthWarp, AMouthWithoutAreaPaintsNothing) {
  cv::Mat frame(120, 160, CV_8UC3);
  cv::RNG(3).fill(frame, cv::RNG::UNIFORM, 0, 255);
  const std::vector<cv::Point2f> line = {{60, 60}, {70, 60}, {80, 60}, {90, 60}, {80, 60}, {70, 60}};
  FaceLayer layer = make_layer(frame, cv::Rect(50, 45, 60, 35), 8);
  layer.mask.setTo(0);
  const cv::Mat before = layer.colour.clone();
  warp_mouth(frame, line, line, layer);
  EXPECT_EQ(cv::countNonZero(layer.mask), 0);
  EXPECT_EQ(cv::norm(layer.colour, before, cv::NORM_INF), 0.0);
}

// Seven points on one row: their centroid's rounding puts the fan's centre
// a hair above it (59.99999), in the row before, and the fan's slivers have
// a little area. The fan's box holds its centre (a box of the contour alone
// did not, and the layer's window was cut outside it: an exception), and
// what the smoothed fill paints beside the row comes from the row.
TEST(MouthWarp, AMouthOnOneRowPaintsThatRow) {
  cv::Mat frame(120, 160, CV_8UC3);
  cv::RNG(3).fill(frame, cv::RNG::UNIFORM, 0, 255);
  const std::vector<cv::Point2f> line = {{60, 60}, {70, 60}, {80, 60}, {90, 60}, {80, 60}, {70, 60}, {65, 60}};
  FaceLayer layer = make_layer(frame, cv::Rect(50, 45, 60, 35), 8);
  layer.mask.setTo(0);
  ASSERT_NO_THROW(warp_mouth(frame, line, line, layer));
  for (int y = 0; y < layer.box.height; ++y)
    for (int x = 0; x < layer.box.width; ++x) {
      if (layer.mask.at<uchar>(y, x) == 0) continue;
      const cv::Vec3b painted = layer.colour.at<cv::Vec3b>(y, x);
      const cv::Vec3b row = frame.at<cv::Vec3b>(60, layer.box.x + x);
      EXPECT_LE(cv::norm(painted, row, cv::NORM_INF), 1.0) << "at " << layer.box.x + x << ", " << layer.box.y + y;
    }
}

TEST(WidenOpening, ARaisedLidOpensOntoTheEyeNotOntoTheOldLid) {
  const Eye eye;
  const std::vector<cv::Point2f> wider = eye.upper_lid_moved(-6);
  FaceLayer layer = eye.rerendered(wider);
  const FaceLayer before{layer.box, layer.colour.clone(), layer.mask.clone(), {}};
  // The band the raised lid uncovered: in the new opening, off the old one,
  // a pixel in from both edges.
  cv::Mat band = inside(wider, layer.box), old_opening = inside(eye.contour, layer.box);
  cv::dilate(old_opening, old_opening, cv::Mat());
  cv::erode(band, band, cv::Mat());
  band &= ~old_opening;
  ASSERT_GT(cv::countNonZero(band), 60);
  // Without the widening the band shows the frame's lid; with it, the eye.
  EXPECT_LT(cv::mean(before.colour, band)[0], 100);
  widen_opening(eye.frame, eye.contour, wider, layer);
  EXPECT_GT(cv::mean(layer.colour, band)[0], 180);
  EXPECT_EQ(cv::countNonZero(layer.mask & band), cv::countNonZero(band)) << "the band is the layer's now";
  // The re-rendered lids and the iris's centre stay as they were.
  cv::Mat changed;
  cv::absdiff(layer.colour, before.colour, changed);
  cv::cvtColor(changed, changed, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::countNonZero(changed & before.mask), 0);
  const cv::Vec3b iris = layer.colour.at<cv::Vec3b>(60 - layer.box.y, 80 - layer.box.x);
  EXPECT_EQ(iris, eye.frame.at<cv::Vec3b>(60, 80));
}

TEST(WidenOpening, ALoweredLidCoversTheEyeAndSquashesNothing) {
  const Eye eye;
  const std::vector<cv::Point2f> narrower = eye.upper_lid_moved(4);
  FaceLayer layer = eye.rerendered(narrower);
  const cv::Mat colour = layer.colour.clone(), mask = layer.mask.clone();
  widen_opening(eye.frame, eye.contour, narrower, layer);
  EXPECT_EQ(cv::norm(layer.colour, colour, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(layer.mask, mask, cv::NORM_INF), 0.0);
}

TEST(WidenOpening, ARaisedLidUncoversTheIrisRoundAndTheWhiteAboveIt) {
  const RaisedLid raised;
  const cv::Rect box = raised.box;
  // Judged above the old lid's edge (what the raised lid uncovered), 8 px
  // inside the new one (off its dark line), and 2 px inside the iris's
  // outline or outside it.
  cv::Mat opened;
  cv::erode(raised.inside(raised.lid_edge), opened, cv::Mat(), {-1, -1}, 8);
  opened &= ~raised.inside(raised.eye.visible);
  cv::Mat iris(box.size(), CV_8U, cv::Scalar(0)), white(box.size(), CV_8U, cv::Scalar(255));
  const cv::Point centre = cv::Point(160, 120) - box.tl();
  cv::circle(iris, centre, int(RealEye::kIrisRadius) - 2, cv::Scalar(255), cv::FILLED);
  cv::circle(white, centre, int(RealEye::kIrisRadius) + 2, cv::Scalar(0), cv::FILLED);
  const cv::Mat opened_iris = opened & iris, opened_white = opened & white;
  ASSERT_GT(cv::countNonZero(opened_iris), 200);
  ASSERT_GT(cv::countNonZero(opened_white), 100);
  const auto share_dark = [](const cv::Mat& grey, const cv::Mat& where) {
    return double(cv::countNonZero((grey < 120) & where)) / cv::countNonZero(where);
  };
  // The fan alone stretches the iris up with the lid, taller than round,
  // into what should be white.
  const cv::Mat stretched = raised.widened(nullptr);
  EXPECT_GT(share_dark(stretched, opened_white), 0.3);
  const cv::Mat round = raised.widened(&raised.visible);
  EXPECT_GT(share_dark(round, opened_iris), 0.98) << "the uncovered iris";
  EXPECT_LT(share_dark(round, opened_white), 0.01) << "the white above it";
  // The iris the frame showed stays as it was.
  cv::Mat frame_grey;
  cv::cvtColor(raised.eye.frame(box), frame_grey, cv::COLOR_BGR2GRAY);
  cv::Mat shown_iris;
  cv::erode(raised.inside(raised.eye.visible), shown_iris, cv::Mat(), {-1, -1}, 3);
  shown_iris &= iris;
  EXPECT_LE(cv::norm(round, frame_grey, cv::NORM_INF, shown_iris), 2.0);
}

TEST(WidenOpening, ARaisedLidUncoversNoSecondCatchlight) {
  RaisedLid raised;
  const cv::Rect box = raised.box;
  // Three more catchlights (brighter than the white, 235) in the iris's
  // upper half: two where the frame shows it clear of the lid, where the
  // iris a lid uncovers is looked for, and one across the lid's edge (104.2
  // px there), as the landmarks often put it (the fan stretched that one up
  // with the lid: 60 bright pixels against 52).
  for (const cv::Point at : {cv::Point(144, 110), cv::Point(176, 110), cv::Point(150, 104)})
    cv::circle(raised.eye.frame, at, 2, cv::Scalar(250, 250, 250), cv::FILLED, cv::LINE_AA);
  cv::Mat frame_grey;
  cv::cvtColor(raised.eye.frame(box), frame_grey, cv::COLOR_BGR2GRAY);
  const cv::Mat out = raised.widened(&raised.visible);
  const int glints = cv::countNonZero(frame_grey > 240);
  ASSERT_GE(glints, 4 * 9);
  EXPECT_LE(cv::countNonZero(out > 240), glints) << "each catchlight once";
  cv::Mat uncovered;  // the iris's disc above the old lid's edge
  cv::circle(uncovered = cv::Mat(box.size(), CV_8U, cv::Scalar(0)), cv::Point(160, 120) - box.tl(),
             int(RealEye::kIrisRadius) - 2, cv::Scalar(255), cv::FILLED);
  uncovered &= ~raised.inside(raised.eye.visible);
  ASSERT_GT(cv::countNonZero(uncovered), 200);
  EXPECT_GT(cv::countNonZero((out < 120) & uncovered), 0.98 * cv::countNonZero(uncovered)) << "the iris";
}

// Rows of `grey`'s column x, from y0 down, until the first white (> 200).
int rows_to_white(const cv::Mat& grey, int x, int y0) {
  int y = y0;
  while (y < grey.rows && grey.at<uchar>(y, x) <= 200) ++y;
  return y - y0;
}
// Rows of `grey`'s column x, from y0 down to y1, that are as dark as the lashes (< 45).
int dark_rows(const cv::Mat& grey, int x, int y0, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y) n += grey.at<uchar>(y, x) < 45;
  return n;
}

TEST(WidenOpening, ARaisedLidKeepsItsEdgeAndLashesAsThick) {
  const RaisedLid raised;
  const cv::Rect box = raised.box;
  cv::Mat frame_grey;
  cv::cvtColor(raised.eye.frame(box), frame_grey, cv::COLOR_BGR2GRAY);
  const cv::Mat fan = raised.widened(nullptr), kept = raised.widened(&raised.visible);
  // Beside the iris (its edge 28 px from the centre), where the frame shows
  // white below the lid: the rows from the skin's loop (20 px above the
  // centre at the top, 45 px once raised) down to the white, and those as
  // dark as the lash line.
  for (const int x : {122, 198}) {
    SCOPED_TRACE(x);
    const int col = x - box.x, middle = 120 - box.y;
    const float height = std::sqrt(1 - std::pow((x - 160) / 60.0f, 2.0f));
    const int old_loop = cvCeil(120 - 20 * height) - box.y, new_loop = cvCeil(120 - 45 * height) - box.y;
    const int band = rows_to_white(frame_grey, col, old_loop), lashes = dark_rows(frame_grey, col, old_loop, middle);
    ASSERT_GE(band, 4);
    ASSERT_GE(lashes, 2);
    // The fan stretches them with the opening; moved whole, they stay.
    EXPECT_GE(rows_to_white(fan, col, new_loop), 2 * band);
    EXPECT_LE(std::abs(rows_to_white(kept, col, new_loop) - band), 1);
    EXPECT_GE(dark_rows(fan, col, new_loop, middle), lashes + 2);
    EXPECT_LE(std::abs(dark_rows(kept, col, new_loop, middle) - lashes), 1);
    // The lashes went up with the lid: none stays behind where it was.
    EXPECT_EQ(dark_rows(kept, col, old_loop, middle), 0);
  }
}

// The same eye turned in the frame (a head rolled 20 or 70 degrees, or
// nearly upside down): the lid rises along the eye's own up-direction, and
// its edge moves whole along it; the iris stays round.
TEST(WidenOpening, ARolledEyesLidMovesWholeAlongTheEyesOwnUp) {
  const RaisedLid upright;
  const cv::Point2f centre(160, 120);
  for (const double degrees : {20.0, 70.0, 160.0}) {
    SCOPED_TRACE(degrees);
    const cv::Mat turn = cv::getRotationMatrix2D(centre, degrees, 1.0);
    const cv::Mat back = cv::getRotationMatrix2D(centre, -degrees, 1.0);
    const auto turned = [&](const std::vector<cv::Point2f>& points) {
      std::vector<cv::Point2f> out;
      cv::transform(points, out, turn);
      return out;
    };
    cv::Mat frame;
    cv::warpAffine(upright.eye.frame, frame, turn, upright.eye.frame.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    const std::vector<cv::Point2f> contour = turned(upright.eye.contour), wider = turned(upright.wider);
    const VisibleEye visible{centre, RealEye::kIrisRadius, turned(upright.eye.visible)};
    // An image turned upright again, grey.
    const auto upright_grey = [&](const cv::Mat& image) {
      cv::Mat grey;
      cv::warpAffine(image, grey, back, image.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
      cv::cvtColor(grey, grey, cv::COLOR_BGR2GRAY);
      return grey;
    };
    const auto widened = [&](const VisibleEye* shown) {
      FaceLayer layer = rerendered_lids(frame, cv::Rect(60, 40, 200, 160), wider);
      widen_opening(frame, contour, wider, layer, shown);
      cv::Mat out = frame.clone();
      layer.colour.copyTo(out(layer.box));
      return upright_grey(out);
    };
    const cv::Mat fan = widened(nullptr), kept = widened(&visible);
    // The frame turned and back again, blurred as the outputs are. Beside
    // the iris, from the skin's loop down to the white: the fan stretches
    // the lid's edge band with the opening; moved whole along the turned
    // eye's up-direction, it stays as thick. (The lash line alone, blurred
    // by three resamplings, is too faint here to count.)
    const cv::Mat frame_grey = upright_grey(frame);
    for (const int x : {122, 198}) {
      SCOPED_TRACE(x);
      const float height = std::sqrt(1 - std::pow((x - 160) / 60.0f, 2.0f));
      const int old_loop = cvCeil(120 - 20 * height), new_loop = cvCeil(120 - 45 * height);
      const int band = rows_to_white(frame_grey, x, old_loop);
      ASSERT_GE(band, 4);
      EXPECT_GE(rows_to_white(fan, x, new_loop), 2 * band);
      EXPECT_LE(std::abs(rows_to_white(kept, x, new_loop) - band), 1);
    }
    // The iris uncovered above the old lid's edge: dark (the iris), not
    // white, and no white above it turned dark.
    cv::Mat iris(kept.size(), CV_8U, cv::Scalar(0)), white(kept.size(), CV_8U, cv::Scalar(255));
    cv::circle(iris, {160, 120}, int(RealEye::kIrisRadius) - 3, cv::Scalar(255), cv::FILLED);
    cv::circle(white, {160, 120}, int(RealEye::kIrisRadius) + 3, cv::Scalar(0), cv::FILLED);
    cv::Mat opened = facecap::inside(upright.lid_edge, cv::Rect({}, kept.size()));
    cv::erode(opened, opened, cv::Mat(), {-1, -1}, 8);
    opened &= ~facecap::inside(upright.eye.visible, cv::Rect({}, kept.size()));
    const cv::Mat opened_iris = opened & iris, opened_white = opened & white;
    ASSERT_GT(cv::countNonZero(opened_iris), 150);
    ASSERT_GT(cv::countNonZero(opened_white), 80);
    EXPECT_GT(cv::countNonZero((kept < 120) & opened_iris), 0.97 * cv::countNonZero(opened_iris));
    EXPECT_LT(cv::countNonZero((kept < 120) & opened_white), 0.02 * cv::countNonZero(opened_white));
  }
}

// What the frame shows of an eye may be degenerate (landmarks collapsed on a
// closed or lost eye, an iris found off the opening or larger than it): the
// widening still paints the opening, from the frame, and nothing breaks.
TEST(WidenOpening, ADegenerateEyeStillWidensFromTheFrame) {
  const RaisedLid raised;
  const std::vector<VisibleEye> eyes = {
      {{160, 120}, RealEye::kIrisRadius, std::vector<cv::Point2f>(6, cv::Point2f(160, 120))},
      {{160, 120}, RealEye::kIrisRadius, {{100, 120}, {220, 120}, {160, 120}}},
      {{-500, 900}, 0.5f, raised.eye.visible},
      {{160, 120}, 500.0f, raised.eye.visible},
  };
  for (size_t k = 0; k < eyes.size(); ++k) {
    SCOPED_TRACE(k);
    FaceLayer layer = rerendered_lids(raised.eye.frame, raised.content, raised.wider);
    const int unset = cv::countNonZero(layer.mask == 0);
    widen_opening(raised.eye.frame, raised.eye.contour, raised.wider, layer, &eyes[k]);
    EXPECT_GT(cv::countNonZero(layer.mask == 0), 0);
    EXPECT_LT(cv::countNonZero(layer.mask == 0), unset / 2) << "the uncovered opening is painted";
  }
}

// Just under the lid's line (within the lid's edge of the landmarks'
// opening) the frame shows the lid's blur: its lashes and its pale wet rim,
// which go up with the lid; and sometimes a catchlight on the cornea, which
// stays where it is.
TEST(WidenOpening, ARaisedLidTakesItsPaleRimAlongAndLeavesTheCatchlightUnderIt) {
  RaisedLid raised;
  const cv::Rect box = raised.box;
  // A pale rim (grey 100: paler than the iris, 67, darker than the lid's
  // skin, 107) along the upper lid's line over the iris, 1 px inside it,
  // and a catchlight (250) just under the line, at x = 170.
  std::vector<cv::Point2f> rim;
  for (float x = 140; x <= 180; x += 1) rim.emplace_back(x, 120 - 16 * std::sqrt(1 - std::pow((x - 160) / 60, 2)) + 1);
  cv::polylines(raised.eye.frame, std::vector<std::vector<cv::Point>>{polygon(rim)}, false, cv::Scalar(100, 100, 100));
  cv::circle(raised.eye.frame, {170, 106}, 1, cv::Scalar(250, 250, 250), cv::FILLED);
  cv::Mat frame_grey;
  cv::cvtColor(raised.eye.frame(box), frame_grey, cv::COLOR_BGR2GRAY);
  const cv::Mat out = raised.widened(&raised.visible);
  for (const int x : {150, 155, 165}) {  // the rim, off the catchlight
    SCOPED_TRACE(x);
    const int y = cvRound(120 - 16 * std::sqrt(1 - std::pow((x - 160) / 60.0, 2)) + 1);
    ASSERT_NEAR(frame_grey.at<uchar>(y - box.y, x - box.x), 100, 3);
    EXPECT_LT(out.at<uchar>(y - box.y, x - box.x), 85) << "the iris where the rim was";
  }
  EXPECT_GT(out.at<uchar>(106 - box.y, 170 - box.x), 240) << "the catchlight stays";
}

}  // namespace facecap
