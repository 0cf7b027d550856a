#include "facecap/detect/iris.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace facecap {
namespace {

// A drawn eye: skin, an almond-shaped opening of white sclera between the six
// landmarks, and a dark iris disc at a known sub-pixel centre, partly under
// the lids, drawn 8x supersampled so that its edge is anti-aliased.
struct DrawnEye {
  cv::Mat grey;
  Landmarks landmarks = zero_landmarks();
};

// `aspect` < 1: the iris seen from the side, an ellipse that narrow; `dark_corner`:
// the opening's inner corner (on the right) shadowed as dark as the iris.
DrawnEye draw_eye(const Vec2d& iris, double iris_radius, double width, double opening, double aspect = 1.0,
                  bool dark_corner = false) {
  constexpr int kSuper = 8;
  const cv::Size size(320, 200);
  cv::Mat big(size.height * kSuper, size.width * kSuper, CV_8U, cv::Scalar(150));
  const Vec2d centre(160, 100);
  const std::array<Vec2d, 6> outline = {
      centre + Vec2d(-width / 2, 0), centre + Vec2d(-width / 6, -opening / 2), centre + Vec2d(width / 6, -opening / 2),
      centre + Vec2d(width / 2, 0),  centre + Vec2d(width / 6, opening / 2),   centre + Vec2d(-width / 6, opening / 2)};
  auto to_big = [&](const Vec2d& p) {
    return cv::Point(int(std::lround((p.x() + 0.5) * kSuper - 0.5)), int(std::lround((p.y() + 0.5) * kSuper - 0.5)));
  };
  std::vector<cv::Point> poly;
  for (const Vec2d& p : outline) poly.push_back(to_big(p));
  cv::Mat opening_mask = cv::Mat::zeros(big.size(), CV_8U);
  cv::fillPoly(opening_mask, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
  cv::Mat eye(big.size(), CV_8U, cv::Scalar(215));
  if (dark_corner) {
    const std::vector<cv::Point> corner = {to_big(outline[3]), to_big(outline[2] + Vec2d(width / 4, 0)),
                                           to_big(outline[4] + Vec2d(width / 4, 0))};
    cv::fillPoly(eye, std::vector<std::vector<cv::Point>>{corner}, cv::Scalar(70));
  }
  const int r = int(std::lround(iris_radius * kSuper));
  cv::ellipse(eye, to_big(iris), cv::Size(int(std::lround(aspect * r)), r), 0, 0, 360, cv::Scalar(70), -1);
  eye.copyTo(big, opening_mask);
  DrawnEye out;
  cv::resize(big, out.grey, size, 0, 0, cv::INTER_AREA);
  for (int k = 0; k < 6; ++k) {
    out.landmarks[36 + k] = outline[k].cast<float>();
    out.landmarks[42 + k] = outline[k].cast<float>();
  }
  return out;
}

// An iris turned toward a shadowed eye corner: a circle's search spills
// into the shadow, the ellipse the head's turn predicts does not.
TEST(Iris, SearchesForTheEllipseOfAnIrisSeenFromTheSide) {
  const Vec2d iris(176.0, 100.4);
  const DrawnEye eye = draw_eye(iris, 11.0, 60.0, 22.0, 0.6, true);
  const std::optional<IrisObservation> ellipse = locate_iris(eye.grey, eye.landmarks, 0, {11.0, 0.6});
  const std::optional<IrisObservation> circle = locate_iris(eye.grey, eye.landmarks, 0, {11.0, 1.0});
  ASSERT_TRUE(ellipse.has_value());
  ASSERT_TRUE(circle.has_value());
  EXPECT_LT((ellipse->centre - iris).norm(), 0.25) << ellipse->centre.transpose();
  EXPECT_GT((circle->centre - iris).norm(), 1.0) << circle->centre.transpose();
}

// The eye of SearchesForTheEllipseOfAnIrisSeenFromTheSide on a face rolled
// 90, 60 and -120 degrees (image and landmarks turned about the image's
// centre): the patch is resampled along the eye, so the ellipse is narrowed
// along the eye's axis, and the iris is found 0.10 / 0.42 / 0.45 px from its
// centre (level: 0.10). Resampled along the image's axes, as before, the
// ellipse lay across the iris or askew: 4.4 px off at each. The eyes' crop
// (eye_crop) finds the same.
TEST(Iris, SearchesForTheEllipseAlongATurnedEyesAxis) {
  const Vec2d iris(176.0, 100.4);
  const DrawnEye level = draw_eye(iris, 11.0, 60.0, 22.0, 0.6, true);
  for (const double degrees : {90.0, 60.0, -120.0}) {
    // Clockwise in the image (y down) by `degrees` about (160, 100).
    const double t = degrees * 3.14159265358979 / 180.0;
    const Eigen::Matrix2d turn{{std::cos(t), -std::sin(t)}, {std::sin(t), std::cos(t)}};
    const Vec2d centre(160, 100);
    auto turned = [&](const Vec2d& p) -> Vec2d { return centre + turn * (p - centre); };
    DrawnEye eye;
    const cv::Matx23d map(turn(0, 0), turn(0, 1), centre.x() - turn.row(0).dot(centre), turn(1, 0), turn(1, 1),
                          centre.y() - turn.row(1).dot(centre));
    cv::warpAffine(level.grey, eye.grey, map, level.grey.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    for (int k = 36; k < 48; ++k) eye.landmarks[k] = turned(level.landmarks[k].cast<double>()).cast<float>();
    const auto found = locate_iris(eye.grey, eye.landmarks, 0, {11.0, 0.6});
    ASSERT_TRUE(found.has_value()) << degrees;
    EXPECT_LT((found->centre - turned(iris)).norm(), 0.6) << degrees << ": " << found->centre.transpose();
    // The eyes' crop holds the turned patch: what it finds is what the whole image gives.
    const cv::Rect crop = eye_crop(eye.grey.size(), eye.landmarks);
    const auto cropped = locate_iris(eye.grey(crop).clone(), eye.landmarks, 0, {11.0, 0.6}, {}, crop.tl());
    ASSERT_TRUE(cropped.has_value()) << degrees;
    EXPECT_LT((cropped->centre - found->centre).norm(), 1e-3) << degrees;
  }
}

TEST(Iris, FindsTheCentreOfAPartlyCoveredDiscToAQuarterPixel) {
  for (const Vec2d& iris : {Vec2d(160.3, 100.6), Vec2d(148.8, 97.2), Vec2d(171.4, 103.5)}) {
    const DrawnEye eye = draw_eye(iris, 11.0, 60.0, 22.0);
    const std::optional<IrisObservation> found = locate_iris(eye.grey, eye.landmarks, 0);
    ASSERT_TRUE(found.has_value());
    EXPECT_LT((found->centre - iris).norm(), 0.25) << found->centre.transpose() << " vs " << iris.transpose();
    EXPECT_NEAR(found->radius, 11.0, 1.0);  // radii are tried in steps of 0.02 eye widths (1.2 px here)
    EXPECT_GT(found->score, 0.8);
  }
}

TEST(Iris, TheSameEyeAtAnotherScaleGivesTheSameAnswer) {
  // The eye is searched at a fixed width, so a small eye is found as well, in proportion.
  const DrawnEye eye = draw_eye(Vec2d(163.2, 101.1), 5.5, 30.0, 11.0);
  const std::optional<IrisObservation> found = locate_iris(eye.grey, eye.landmarks, 1, {5.5});
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((found->centre - Vec2d(163.2, 101.1)).norm(), 0.25);
}

// A frame's eyes kept without the frame (eye_crop, searched with its
// origin) give what the whole frame gives, to the last bit: in the middle
// of the image, where the crop is cut by the image's edge, and where the
// resampled patch reaches past that edge.
TEST(Iris, AnEyeCropFindsWhatTheWholeImageGives) {
  struct Case {
    double width, opening;
    Vec2d shift;  // of both eyes' landmarks and the drawn eye (in whole pixels)
  };
  // The eye's box with its margin spans x 121-199, y 80-120 before the
  // shift: shifted to x 0 or y 0 the crop is cut by the image's edge; to
  // x 319 or y 199 (the last pixels) the patch's last samples fall past it.
  int found = 0;
  for (const Case& c : {Case{60, 22, {0, 0}}, Case{24, 9, {0, 0}}, Case{60, 22, {-121, 0}}, Case{60, 22, {120, 0}},
                        Case{60, 22, {0, -80}}, Case{60, 22, {0, 79}}}) {
    const Vec2d iris = Vec2d(163.4, 101.2) + c.shift;
    DrawnEye eye = draw_eye(Vec2d(163.4, 101.2), 0.2 * c.width, c.width, c.opening);
    // Texture, so that where each sample falls matters.
    cv::Mat noise(eye.grey.size(), CV_8U);
    cv::RNG(7).fill(noise, cv::RNG::UNIFORM, 0, 25);
    eye.grey += noise;
    const cv::Matx23d move(1, 0, c.shift.x(), 0, 1, c.shift.y());
    cv::warpAffine(eye.grey, eye.grey, move, eye.grey.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
    for (int k = 36; k < 48; ++k) eye.landmarks[k] += c.shift.cast<float>();
    const cv::Rect crop = eye_crop(eye.grey.size(), eye.landmarks);
    ASSERT_FALSE(crop.empty());
    EXPECT_LT(crop.area(), eye.grey.size().area() / 3);
    const cv::Mat eyes_only = eye.grey(crop).clone();
    for (const IrisExpectation& expected : {IrisExpectation{}, IrisExpectation{0.2 * c.width, 0.8}}) {
      const auto whole = locate_iris(eye.grey, eye.landmarks, 0, expected);
      const auto cropped = locate_iris(eyes_only, eye.landmarks, 0, expected, {}, crop.tl());
      ASSERT_TRUE(whole.has_value()) << c.shift.transpose();
      ASSERT_TRUE(cropped.has_value()) << c.shift.transpose();
      ++found;
      EXPECT_LT((whole->centre - iris).norm(), 1.0) << c.shift.transpose();
      EXPECT_EQ(whole->centre, cropped->centre) << c.shift.transpose();
      EXPECT_EQ(whole->radius, cropped->radius);
      EXPECT_EQ(whole->score, cropped->score);
    }
    // One pixel further, the eye is cut off in both.
    for (int k = 36; k < 48; ++k) eye.landmarks[k] += (c.shift / std::max(1.0, c.shift.norm())).cast<float>();
    if (c.shift.norm() > 0) {
      const cv::Rect past = eye_crop(eye.grey.size(), eye.landmarks);
      EXPECT_FALSE(locate_iris(eye.grey, eye.landmarks, 0).has_value()) << c.shift.transpose();
      EXPECT_FALSE(locate_iris(eye.grey(past).clone(), eye.landmarks, 0, {}, {}, past.tl()).has_value());
    }
  }
  EXPECT_EQ(found, 12);
}

TEST(Iris, AClosedBlankTinyOrCutOffEyeGivesNothing) {
  const DrawnEye closed = draw_eye(Vec2d(160, 100), 11.0, 60.0, 6.0);  // opening 0.1 of the width
  EXPECT_FALSE(locate_iris(closed.grey, closed.landmarks, 0).has_value());

  DrawnEye blank = draw_eye(Vec2d(160, 100), 11.0, 60.0, 22.0);
  blank.grey.setTo(cv::Scalar(180));
  EXPECT_FALSE(locate_iris(blank.grey, blank.landmarks, 0).has_value());

  const DrawnEye tiny = draw_eye(Vec2d(160, 100), 1.5, 8.0, 3.0);
  EXPECT_FALSE(locate_iris(tiny.grey, tiny.landmarks, 0).has_value());

  DrawnEye cut_off = draw_eye(Vec2d(160, 100), 11.0, 60.0, 22.0);
  for (int k = 36; k < 48; ++k) cut_off.landmarks[k].x() -= 128.0f;  // the eye's left corner at x = 2
  EXPECT_FALSE(locate_iris(cut_off.grey, cut_off.landmarks, 0).has_value());

  EXPECT_FALSE(locate_iris(cv::Mat(), closed.landmarks, 0).has_value());
  cv::Mat colour;
  cv::cvtColor(closed.grey, colour, cv::COLOR_GRAY2BGR);
  EXPECT_FALSE(locate_iris(colour, closed.landmarks, 0).has_value());
}

}  // namespace
}  // namespace facecap
