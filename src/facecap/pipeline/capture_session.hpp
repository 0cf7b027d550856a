#pragma once
// Capture of an input, frame by frame: decode, landmarks (detection and box
// tracking), coarse fit. Frames reach the sink in order, each with its status;
// the first ones arrive together once the identity and focal length are solved.
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/detect/face_tracker.hpp"
#include "facecap/detect/iris.hpp"
#include "facecap/detect/shot_cut.hpp"
#include "facecap/fit/coarse_tracker.hpp"
#include "facecap/fit/gaze.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/input_damage.hpp"

namespace facecap {

struct CaptureOptions {
  CoarseFitOptions fit;
  FaceTrackerOptions tracker;
  int max_frames = 0;  // 0: the whole input
  // Where the jobs start reading their input, in seconds (open_input): a
  // video's frames from there on, on the video's own timeline.
  double start_seconds = 0;
  bool keep_images = false;  // hand each frame's image to the sink
  bool gaze = true;          // find the irises and the gaze, which guides the eyeLook weights (gaze.hpp)
  // Shot cuts (shot_cut.hpp) start a new shot: the identity and focal length
  // are solved again over its first frames, so that a video cutting between
  // two people (or two lenses) is not fitted with the first one's face.
  bool shot_cuts = true;
  ShotCutOptions shot_cut;
  bool quiet = false;  // no progress bar
  // Find a frame's landmarks while the frame before is fitted, on another
  // thread (face_capture.hpp); the same result either way.
  bool pipelined = true;

  // Throws facecap::Error naming the first option out of range (the fit's
  // included); run_capture and run_capture_all_faces call it before reading.
  void check() const;
};

struct CapturedFrame {
  int index = 0;
  double time = 0.0;
  TrackStatus status = TrackStatus::kLost;  // lost also when the fit rejected the landmarks
  int faces_seen = 0;                       // faces the detector found in this frame (0 when it did not run)
  CoarseFit fit;                            // with the irises and gaze when CaptureOptions::gaze
  IdentityEstimate identity;  // the identity and focal the fit used (a copy: frames may outlive the session)
  int shot = 0;               // which shot of the input (CaptureOptions::shot_cuts), from 0
  cv::Mat image;              // when CaptureOptions::keep_images (black where the input could not give the frame)
  std::string error;          // why the frame could not be read (it is then lost); "" otherwise
  bool damaged = false;       // decoded with damage concealed (Frame::damaged): the input is corrupt
};

// Milliseconds spent per stage, summed over frames.
struct StageTimings {
  double setup_ms = 0;      // loading the landmark and detector models
  double decode_ms = 0;     // on the decode thread, concurrent with the rest
  double detect_ms = 0;     // HOG face detector (start, losses, periodic checks)
  double landmarks_ms = 0;  // 68-point shape predictor
  double iris_ms = 0;       // the iris search (iris.hpp), run by the fit but not counted in fit_ms
  double fit_ms = 0;        // per-frame coarse fit
  double identity_ms = 0;   // the one-off identity and focal solve
  double total_s = 0;       // wall time of the whole run
  int frames = 0;
  // Frames per second after setup: frames / (total - setup).
  double fps() const { return total_s * 1000 > setup_ms ? frames / (total_s - setup_ms / 1000) : 0.0; }
};

struct CaptureSummary {
  int frames = 0;
  int lost = 0;
  int redetected = 0;
  int rejected = 0;         // frames whose landmarks the fit turned down (the tracker then detects afresh)
  int most_faces = 0;       // the most faces the detector found in one frame (--face chooses which is tracked)
  int unreadable = 0;       // frames the input could not give (each also lost)
  std::string first_error;  // the first of those frames' reasons
  InputDamage damage;       // what a corrupt input cost (its damaged frames counted lost or not)
  // The identity and focal length of the first shot with a face (the only
  // shot unless the input cuts), and of every shot with a face.
  IdentityEstimate identity;
  struct Shot {
    int index = 0;        // CapturedFrame::shot
    int first_frame = 0;  // the input's frame number where it starts
    IdentityEstimate identity;
  };
  std::vector<Shot> shots;
  int cuts = 0;  // shot cuts found
  // A camera ended by Ctrl-C (interrupt.hpp: set_interrupt_ends_input): the
  // frames before it are all delivered, and the job completes with them.
  bool stopped_by_user = false;
  StageTimings timings;
  InputInfo input;
};

using FrameSink = std::function<void(const CapturedFrame&)>;

// One line for the user where some frames could not be read ("N frame(s) of
// WHAT could not be read, ..."), "" where every frame could.
std::string unreadable_frames_note(const CaptureSummary& summary, const std::string& what);
// The unreadable frames' note and the input's damage (input_damage_note)
// in one line, "" where every frame was read whole and the input read to
// its end.
std::string damaged_input_note(const CaptureSummary& summary, const std::string& what);
// "no face found in any frame of WHAT: CONSEQUENCE", and the input's damage
// where it had any (input_damage_note: a corrupt video may be why no face shows).
std::string no_face_error(const std::string& what, const InputDamage& damage, const std::string& consequence);

CaptureSummary run_capture(const FaceModel& model, FrameSource& source, CaptureOptions options, const FrameSink& sink);

}  // namespace facecap
