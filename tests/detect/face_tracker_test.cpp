#include "facecap/detect/face_tracker.hpp"

#include <gtest/gtest.h>

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

}  // namespace facecap
