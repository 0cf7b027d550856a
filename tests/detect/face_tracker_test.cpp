#include "facecap/detect/face_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "facecap/io/input.hpp"
#include "test_support.hpp"

namespace facecap {

TEST(FaceTracker, TracksATalkingHeadWithoutLosingIt) {
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const LandmarkDetector detector;
  FaceTracker tracker(detector);
  auto source = open_input(video.string());
  Frame frame;
  int lost = 0, full_detections = 0, frames = 0;
  std::optional<Landmarks> previous;
  float max_jump = 0;
  while (frames < 100 && source->read(frame)) {
    const TrackedFace face = tracker.next(frame.image);
    lost += face.status == TrackStatus::kLost;
    full_detections += face.full_detection;
    if (previous && face.status != TrackStatus::kLost) {
      max_jump = std::max(max_jump, landmark_nme(face.landmarks, *previous));
    }
    if (face.status != TrackStatus::kLost) previous = face.landmarks;
    ++frames;
  }
  EXPECT_EQ(frames, 100);
  EXPECT_EQ(lost, 0);
  // The whole frame is searched at the start only; later frames check a crop.
  EXPECT_LE(full_detections, 2);
  // No landmark set jumps by a large share of the face between frames.
  EXPECT_LT(max_jump, 0.08f);
}

TEST(FaceTracker, ReportsLostFramesAndRecoversWhenTheFaceReturns) {
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const LandmarkDetector detector;
  FaceTracker tracker(detector);
  auto source = open_input(video.string());
  Frame frame;
  ASSERT_TRUE(source->read(frame));
  const cv::Mat face_image = frame.image.clone();
  EXPECT_NE(tracker.next(face_image).status, TrackStatus::kLost);
  const cv::Mat blank(face_image.size(), face_image.type(), cv::Scalar(90, 90, 90));
  int lost = 0;
  for (int i = 0; i < 6; ++i) lost += tracker.next(blank).status == TrackStatus::kLost;
  EXPECT_GE(lost, 3);  // lost within the check interval
  EXPECT_EQ(tracker.next(blank).status, TrackStatus::kLost);
  EXPECT_EQ(tracker.next(face_image).status, TrackStatus::kRedetected);
}

// The webcam clip shrunk to a quarter of its size on a grey 400x300 frame: a
// face 16 px between the outer eye corners, below what the detector finds at
// the frame's own size. The search at twice the size finds it, and the
// landmarks follow it from there as they follow the full-size face: the
// per-frame check upscales its crop to the detector's window (without that,
// it re-anchors the landmarks on wrong boxes: median NME 0.12 against 0.013).
TEST(FaceTracker, FindsAndFollowsAFaceSmallerThanTheDetectorsWindow) {
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  constexpr double kShrink = 0.25;
  const Vec2f offset(150.0f, 110.0f);
  const LandmarkDetector detector;
  FaceTrackerOptions without_fine_search;
  without_fine_search.fine_search_every = 0;
  FaceTracker full_size(detector), small(detector), small_without_fine_search(detector, without_fine_search);
  auto source = open_input(video.string());
  Frame frame;
  int frames = 0, lost = 0, lost_without = 0;
  std::vector<float> errors;
  float eye_distance = 0;
  while (frames < 30 && source->read(frame)) {
    cv::Mat shrunk;
    cv::resize(frame.image, shrunk, cv::Size(), kShrink, kShrink, cv::INTER_AREA);
    cv::Mat canvas(frame.image.size(), frame.image.type(), cv::Scalar(110, 110, 110));
    shrunk.copyTo(canvas(cv::Rect(int(offset.x()), int(offset.y()), shrunk.cols, shrunk.rows)));
    const TrackedFace reference = full_size.next(frame.image);
    const TrackedFace face = small.next(canvas);
    lost_without += small_without_fine_search.next(canvas).status == TrackStatus::kLost;
    ++frames;
    if (face.status == TrackStatus::kLost) {
      ++lost;
      continue;
    }
    ASSERT_NE(reference.status, TrackStatus::kLost);
    // Where the full-size landmarks land in the shrunk image (pixel centres at integers).
    Landmarks expected = reference.landmarks;
    for (auto& p : expected) p = (p + Vec2f(0.5f, 0.5f)) * float(kShrink) - Vec2f(0.5f, 0.5f) + offset;
    errors.push_back(landmark_nme(face.landmarks, expected));
    eye_distance = outer_eye_distance(expected);
  }
  EXPECT_EQ(frames, 30);
  EXPECT_LT(eye_distance, 18.0f);   // the face is small
  EXPECT_EQ(lost_without, frames);  // the search at the frame's size never sees it
  EXPECT_EQ(lost, 0);               // the search at twice the size does
  ASSERT_FALSE(errors.empty());
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.03f) << "median NME against the full-size face's landmarks";
}

}  // namespace facecap
