#include "facecap/pipeline/refine_stage.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
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
// eight places are full (the queue of 3, a frame in each of its three threads
// and one handed between each two), and the stage never waits for a frame.
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
  // The last 8 pushes wait for a 10 ms frame each.
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

// A consumer that fails (a full disk under a writer) stops the stage: the
// failure reaches capture's thread, from push() or finish(), and the frames
// after it are not consumed.
TEST(RefineStage, AConsumersFailureReachesCapture) {
  FACECAP_REQUIRE_MODEL(model);
  int consumed = 0;
  RefineStage stage(*model, RefineOptions{}, [&](const RefinedFrame& r) {
    if (r.frame.index == 3) throw std::runtime_error("disk full");
    ++consumed;
  });
  std::string message;
  try {
    for (int i = 0; i < 40; ++i) stage.push(lost_frame(i));
    stage.finish();
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_EQ(message, "disk full");
  EXPECT_EQ(consumed, 3);
}

}  // namespace facecap
