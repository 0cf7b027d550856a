#pragma once
// One face's capture through an input, frame by frame: its landmarks
// (FaceTracker), its coarse fit (CoarseTracker), the frames held until their
// fit is final, and its shots. run_capture drives one; track --all-faces one
// per face, on one decoding pass (face_roster.hpp).
#include <future>
#include <map>
#include <optional>

#include "facecap/core/serial_worker.hpp"
#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/frame_loop.hpp"

namespace facecap {

// With CaptureOptions::pipelined, a frame's landmarks are found while the
// fit of the frame before runs on another thread (two cores: about 1.5 times
// the frames a second). The result is the same as one after the other: where
// that fit rejects its frame's landmarks (FaceTracker::reset), the frame
// tracked meanwhile is taken back and tracked again from the reset.
class FaceCapture {
 public:
  // `info`: the input as this face's capture sees it (its first frame is
  // where the face was first found). `shot`: the input's shot it starts in.
  FaceCapture(const FaceModel& model, const LandmarkDetector& landmarks, const CaptureOptions& options,
              const InputInfo& info, FrameSink sink, int shot = 0);
  FaceCapture(const FaceCapture&) = delete;  // its iris searches hold a reference into it
  FaceCapture& operator=(const FaceCapture&) = delete;

  // One frame; `cut` ends the shot before it. frame_faces: FaceTracker::next's.
  // Frames reach the sink once their fit is final.
  const TrackedFace& push(const DecodedFrame& decoded, bool cut, const FaceTracker::FrameFaces& frame_faces = {});
  // The input ended: the frames still waiting are fitted and delivered. The
  // summary's timings hold this face's stages (not decoding, setup or the total).
  CaptureSummary finish();

  const FaceTracker& face_tracker() const { return face_tracker_; }
  // Turns the pipelining (CaptureOptions::pipelined) on or off from the next
  // frame on: track --all-faces pipelines a face while it is the only one.
  void set_pipelined(bool pipelined) { options_.pipelined = pipelined; }

 private:
  struct Waiting {
    TrackStatus status;
    int faces_seen;
    cv::Mat image;
    std::string error;
    bool damaged;
    int shot;
  };
  // One frame's landmarks for the fit (track()'s output).
  struct FitJob {
    int index = 0;
    double time = 0;
    std::optional<Landmarks> landmarks;
    IrisSearch iris_search;
  };
  struct FitResult {
    std::vector<CoarseFit> fits;
    bool rejected = false;  // the fit of the job's own frame rejected its landmarks
  };
  FitJob track(const DecodedFrame& decoded, const FaceTracker::FrameFaces& frame_faces);
  FitResult fit(FitJob job);
  // Waits for the fit in flight, if any, and delivers it; where it rejected
  // its frame, resets the face tracker and returns true.
  bool finish_pending_fit();
  void deliver(const std::vector<CoarseFit>& fits);
  std::vector<CoarseFit> timed(const std::function<std::vector<CoarseFit>()>& call);
  void end_shot();

  CaptureOptions options_;
  FaceTracker face_tracker_;
  CoarseTracker tracker_;
  FrameSink sink_;
  CaptureSummary summary_;
  std::map<int, Waiting> waiting_;  // frames whose fit is not final yet
  int shot_ = 0;
  int shot_start_ = 0;
  TrackedFace last_;
  std::future<FitResult> pending_;
  SerialWorker fitter_{"facecap-fit"};  // last: destroyed first, so a fit in flight ends before what it uses
};

}  // namespace facecap
