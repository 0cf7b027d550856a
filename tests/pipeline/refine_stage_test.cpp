#include "facecap/pipeline/refine_stage.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "test_support.hpp"

namespace facecap {

namespace {

using std::chrono::milliseconds;

// Frames with no face: the stage hands them on without refining, so its
// accounting can be checked against sleeps alone.
CapturedFrame lost_frame(int index) {
  CapturedFrame f;
  f.index = index;
  return f;
}

}  // namespace

// A consumer slower than capture: capture waits in push() once the stage's
// six places are full (the queue of 3, a frame in each of its two threads and
// one handed between them), and the stage never waits for a frame.
TEST(RefineStage, ASlowStageMakesCaptureWaitAndSaysSo) {
  FACECAP_REQUIRE_MODEL(model);
  constexpr int kFrames = 16;
  int consumed = 0;
  RefineStage stage(*model, RefineOptions{}, [&](const RefinedFrame&) {
    std::this_thread::sleep_for(milliseconds(10));
    ++consumed;
  });
  for (int i = 0; i < kFrames; ++i) stage.push(lost_frame(i));
  stage.finish();
  const RefineStageTimings& t = stage.timings();
  EXPECT_EQ(consumed, kFrames);
  EXPECT_EQ(stage.frames(), kFrames);
  EXPECT_EQ(stage.refined_frames(), 0);
  // The stage holds 8 frames (3 queued, 1 on each of its three threads and 1
  // between each two of them); the last 8 pushes wait for a 10 ms frame each.
  EXPECT_GT(t.push_wait_ms, 60.0);
  EXPECT_GE(t.consumer_ms, 10.0 * kFrames);
  EXPECT_GE(t.first_to_last_ms, t.consumer_ms);
  EXPECT_LT(t.idle_ms, t.consumer_ms);
}

// Capture slower than the stage: the stage idles between frames, and the
// wait before the first frame is its start-up, not idle time.
TEST(RefineStage, ASlowCaptureLeavesTheStageIdleAfterItsStartUp) {
  FACECAP_REQUIRE_MODEL(model);
  constexpr int kFrames = 6;
  RefineStage stage(*model, RefineOptions{}, [](const RefinedFrame&) {});
  std::this_thread::sleep_for(milliseconds(30));  // capture's own start-up
  for (int i = 0; i < kFrames; ++i) {
    stage.push(lost_frame(i));
    std::this_thread::sleep_for(milliseconds(10));
  }
  stage.finish();
  const RefineStageTimings& t = stage.timings();
  EXPECT_EQ(stage.frames(), kFrames);
  EXPECT_GE(t.startup_ms, 30.0);
  EXPECT_GE(t.idle_ms, 10.0 * (kFrames - 3));  // 5 gaps of 10 ms, less scheduling delays
  EXPECT_LT(t.consumer_ms, t.idle_ms);
}

}  // namespace facecap
