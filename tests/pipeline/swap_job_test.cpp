// SwapJob end to end on real footage.
#include "facecap/pipeline/swap_job.hpp"

#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "facecap/core/temp_dir.hpp"
#include "facecap/pipeline/track_job.hpp"
#include "test_support.hpp"

namespace facecap {

// bench swap --tracked-first captures the whole target before the swap
// starts: the swap then sees the same frames with the same fits, so it writes
// the same output, frame for frame, as the swap that streams beside capture.
TEST(SwapJob, ASwapOfATargetTrackedFirstIsTheStreamedSwap) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(target, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(photo, "portrait_biden.jpg");
  TempDir dir;
  std::map<int, cv::Mat> outputs[2];
  for (const bool first : {false, true}) {
    SwapJobOptions o;
    o.capture.quiet = true;
    o.capture.max_frames = 40;
    o.track_first = first;
    o.on_output_frame = [&](int index, const cv::Mat& image) { outputs[first][index] = image.clone(); };
    const SwapSummary s = run_swap(*model, photo.string(), target.string(), dir.path() / "out.mp4", o);
    EXPECT_EQ(s.timings.swapped, 40) << first;
  }
  ASSERT_EQ(outputs[0].size(), 40u);
  ASSERT_EQ(outputs[1].size(), 40u);
  for (const auto& [index, image] : outputs[0]) {
    EXPECT_EQ(cv::norm(image, outputs[1].at(index), cv::NORM_INF), 0.0) << "frame " << index;
  }
}

}  // namespace facecap
