#pragma once
// One face's capture through an input, frame by frame: its landmarks
// (FaceTracker), its coarse fit (CoarseTracker), the frames held until their
// fit is final, and its shots. run_capture drives one; track --all-faces one
// per face, on one decoding pass (face_roster.hpp).
#include <map>

#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/frame_loop.hpp"

namespace facecap {

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

 private:
  struct Waiting {
    TrackStatus status;
    int faces_seen;
    cv::Mat image;
    std::string error;
    int shot;
  };
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
};

}  // namespace facecap
