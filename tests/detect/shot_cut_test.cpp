#include "facecap/detect/shot_cut.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "facecap/io/input.hpp"
#include "test_support.hpp"

namespace facecap {

namespace {

std::vector<cv::Mat> grey_frames(const std::string& name, int max_frames) {
  std::vector<cv::Mat> out;
  auto source = open_input((default_data_dir() / name).string());
  for (Frame f; int(out.size()) < max_frames && source->read(f);) {
    cv::Mat grey;
    cv::cvtColor(f.image, grey, cv::COLOR_BGR2GRAY);
    out.push_back(grey);
  }
  return out;
}

}  // namespace

// On every clip of ../shared/data, whole: no cut (the lowest correlation, a
// hand across the face or an exposure step, stays far above the threshold).
TEST(ShotCut, NoneWithinTheClips) {
  FACECAP_REQUIRE_DATA(any, "talking_webcam_400x300.mp4");
  for (const char* name : {"address_720p_a.mp4", "address_720p_b.mp4", "emotions_pexels_640x360.mp4",
                           "talking_webcam_400x300.mp4", "talking_webcam2_400x300.mp4"}) {
    ShotCutDetector cuts;
    int found = 0;
    double lowest = 1.0;
    for (const cv::Mat& grey : grey_frames(name, 100000)) {
      found += cuts.next(grey);
      lowest = std::min(lowest, cuts.last_correlation());
    }
    EXPECT_EQ(found, 0) << name;
    EXPECT_GT(lowest, 0.75) << name;
  }
}

// One clip joined to another (at another size, as an edit scales it) is one
// cut, where it joins; so is the same join through black frames (a fade),
// and an exposure jump is none.
TEST(ShotCut, OneAtEachJoinOfTwoClips) {
  FACECAP_REQUIRE_DATA(any, "address_720p_a.mp4");
  const std::vector<cv::Mat> a = grey_frames("address_720p_a.mp4", 10);
  const std::vector<cv::Mat> b = grey_frames("talking_webcam2_400x300.mp4", 10);
  std::vector<cv::Mat> joined = a;
  for (const cv::Mat& g : b) {
    cv::Mat scaled;
    cv::resize(g, scaled, a.front().size());
    joined.push_back(scaled);
  }
  ShotCutDetector cuts;
  std::vector<int> at;
  double at_join = 1.0;
  for (size_t i = 0; i < joined.size(); ++i) {
    if (cuts.next(joined[i])) at.push_back(int(i));
    if (i == 10) at_join = cuts.last_correlation();
  }
  EXPECT_EQ(at, std::vector<int>{10});
  EXPECT_LT(at_join, 0.25);

  // Through black: frames 10-14 black, the other clip from 15.
  ShotCutDetector through_black;
  at.clear();
  std::vector<cv::Mat> faded(joined.begin(), joined.begin() + 10);
  for (int i = 0; i < 5; ++i) faded.push_back(cv::Mat::zeros(a.front().size(), CV_8U));
  faded.insert(faded.end(), joined.begin() + 10, joined.end());
  for (size_t i = 0; i < faded.size(); ++i)
    if (through_black.next(faded[i])) at.push_back(int(i));
  EXPECT_EQ(at, std::vector<int>{15});

  // The first clip twice as bright from frame 5 (an exposure step): no cut.
  ShotCutDetector exposure;
  int found = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    cv::Mat g = a[i];
    if (i >= 5) g.convertTo(g, -1, 1.6, 10.0);
    found += exposure.next(g);
  }
  EXPECT_EQ(found, 0);
  // An unreadable frame (empty) is no cut, and no reference.
  EXPECT_FALSE(exposure.next(cv::Mat()));
}

}  // namespace facecap
