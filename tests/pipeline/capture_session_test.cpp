#include "facecap/pipeline/capture_session.hpp"

#include <gtest/gtest.h>

#include <csignal>

#include "facecap/core/error.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/io/input.hpp"
#include "facecap/pipeline/face_roster.hpp"
#include "test_support.hpp"

namespace facecap {
namespace {

// A video read as if it were a camera (which the test machine has none of),
// whose user presses Ctrl-C when `stop_after` frames have been read.
class PressedCtrlC : public FrameSource {
 public:
  PressedCtrlC(std::unique_ptr<FrameSource> video, InputKind kind, int stop_after)
      : video_(std::move(video)), info_(video_->info()), stop_after_(stop_after) {
    info_.kind = kind;
    if (kind == InputKind::kCamera) info_.frames = -1;
  }
  const InputInfo& info() const override { return info_; }
  bool read(Frame& frame) override {
    if (++reads_ == stop_after_) std::raise(SIGINT);
    return video_->read(frame);
  }

 private:
  std::unique_ptr<FrameSource> video_;
  InputInfo info_;
  int stop_after_;
  int reads_ = 0;
};

struct InterruptHandler {
  InterruptHandler() { install_interrupt_handler(); }
  ~InterruptHandler() {
    clear_interrupt();
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
};

// Captures `video` read as an input of `kind`, with Ctrl-C pressed at its
// `stop_after`th read.
CaptureSummary capture_pressing_ctrl_c(const FaceModel& model, const std::filesystem::path& video, InputKind kind,
                                       int stop_after, const FrameSink& sink) {
  const InterruptHandler handler;
  PressedCtrlC source(open_input(video.string()), kind, stop_after);
  CaptureOptions options;
  options.quiet = true;
  const CaptureSummary s = run_capture(model, source, options, sink);
  EXPECT_FALSE(interrupted());  // a Ctrl-C that ended the input is handled: the job goes on to write its files
  return s;
}

// A camera has no end but the user's: Ctrl-C ends the input, and every frame
// captured until then is delivered, fitted with the identity solved from them.
TEST(CaptureSession, ACameraStoppedByCtrlCDeliversWhatItCaptured) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  int delivered = 0, tracked = 0;
  const CaptureSummary s = capture_pressing_ctrl_c(*model, video, InputKind::kCamera, 45, [&](const CapturedFrame& f) {
    EXPECT_EQ(f.index, delivered);
    ++delivered;
    tracked += f.status != TrackStatus::kLost;
  });
  EXPECT_TRUE(s.stopped_by_user);
  EXPECT_EQ(delivered, s.frames);
  // Ctrl-C came as the decoder began its 45th read: it had queued 44 frames,
  // of which the queue holds at most 4, so the fit had taken at least 40,
  // and the one taken when it saw the signal is not fitted.
  EXPECT_GE(s.frames, 39);
  EXPECT_LE(s.frames, 44);
  EXPECT_EQ(tracked, s.frames);
  EXPECT_EQ(s.identity.frames_used, 30);
}

// Anything else stopped by Ctrl-C is a job that did not finish: it throws,
// and the job's outputs are never committed.
TEST(CaptureSession, AVideoStoppedByCtrlCThrows) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  EXPECT_THROW(capture_pressing_ctrl_c(*model, video, InputKind::kVideo, 20, [](const CapturedFrame&) {}), Error);
}

// track --all-faces reads a camera once for every face: Ctrl-C ends it, and
// each face's frames until then are delivered.
TEST(CaptureSession, EveryFaceOfACameraStoppedByCtrlCIsDelivered) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  const InterruptHandler handler;
  PressedCtrlC source(open_input(video.string()), InputKind::kCamera, 45);
  CaptureOptions options;
  options.quiet = true;
  int delivered = 0;
  const AllFacesSummary s =
      run_capture_all_faces(*model, source, options, {}, [&](const FoundFace& face, const InputInfo& info) {
        EXPECT_EQ(face.first_frame, 0);
        EXPECT_EQ(info.kind, InputKind::kCamera);
        return [&](const CapturedFrame& f) { EXPECT_EQ(f.index, delivered++); };
      });
  EXPECT_FALSE(interrupted());
  EXPECT_TRUE(s.stopped_by_user);
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(delivered, s.captures[0].frames);
  EXPECT_EQ(s.captures[0].frames, s.timings.frames);
  EXPECT_GE(s.captures[0].frames, 39);
  EXPECT_EQ(s.captures[0].lost, 0);
}

}  // namespace
}  // namespace facecap
