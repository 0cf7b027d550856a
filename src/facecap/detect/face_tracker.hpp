#pragma once
// Per-frame 68-point landmarks for a video: the face box is predicted from the
// previous frame's landmarks, and the HOG detector searches the whole frame
// (downscaled, and at twice that size where it finds nothing) only at the
// start and after a loss, and checks each tracked face on a small crop.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/detect/face_detector.hpp"
#include "facecap/detect/landmark_detector.hpp"
#include "facecap/detect/turned_faces.hpp"
#include "facecap/detect/upright_view.hpp"

namespace facecap {

// Intersection over union of two boxes.
float box_overlap(const Box& a, const Box& b);

enum class TrackStatus { kTracked, kRedetected, kLost };
const char* to_string(TrackStatus status);

// Which face to follow where the detector finds several (an interview's
// two-shot, a crowd): the largest (the default), the leftmost or rightmost
// in the picture, or the one nearest a point. It chooses where a shot starts
// and once the face has been gone a while (FaceTrackerOptions::follow_frames);
// before that, the tracker takes up only a face where its face was last seen,
// so that a face that turns away or is covered for a moment is not swapped for
// another one beside it.
struct FacePick {
  enum class Rule { kLargest, kLeftmost, kRightmost, kNearest };
  Rule rule = Rule::kLargest;
  Vec2f point{0, 0};  // kNearest: pixels of the frame
};
// "largest", "left", "right" or "X,Y" (pixels); throws facecap::Error
// otherwise, saying what the text must be (the caller names the option).
FacePick parse_face_pick(std::string_view text);
// For messages: "largest", "leftmost", "rightmost" or "one nearest (X, Y)".
std::string describe(const FacePick& pick);

// The face `pick` chooses among `faces` (not empty).
const FaceDetection& choose_face(const std::vector<FaceDetection>& faces, const FacePick& pick);

struct FaceTrackerOptions {
  FacePick pick;
  FaceDetectorOptions detector;
  // Re-check every this many tracked frames that a face is still in the box
  // (detector on a crop 1.6 times the face, scaled to 130 px: about 1.3 ms at
  // any resolution); 0 disables the check. Every frame by default, so that a
  // frame without a face is reported lost rather than given the last face's shape.
  int verify_every = 1;
  // When the detector's box and the box implied by the tracked landmarks
  // overlap less than this (intersection over union), the landmarks are
  // re-anchored on the detector's box (status `redetected`).
  float min_box_overlap = 0.55f;
  // A tracked box that grows or shrinks by more than this factor between
  // frames is treated as a loss.
  float max_scale_change = 1.35f;
  // Faces smaller than this (outer-eye distance, pixels) count as lost.
  float min_eye_distance = 12.0f;
  // Where the whole frame holds no face the detector can see, it is searched
  // again at twice the size (detector.upsample + 1): faces down to half the
  // smallest it finds otherwise (at 1280x720, 80 px rather than 160 px wide;
  // a speaker in a wide shot), at about 4 times the time (52 ms against 14
  // ms at 1280x720; `detect_bench`). That happens on the first frame without
  // a face and every this many after it, so that a long stretch with no face
  // costs little more; 0 never searches at twice the size.
  int fine_search_every = 8;
  // For this many frames after the face was last seen in a shot, a face is
  // taken up again only within follow_radius face sizes (the landmarks' box)
  // of where it was: until then a frame where only someone else shows is
  // lost, not fitted with this face's identity. Then `pick` chooses again.
  int follow_frames = 50;
  float follow_radius = 1.0f;
  // The landmarks handed out are the mean of the cascade on the frame and on
  // its mirror image (LandmarkDetector::detect; the tracker's own decisions
  // are taken on the first pass alone); false hands out the first pass.
  bool mirror_average = true;
  // A face rolled past what the detector and the cascade take (about 40
  // degrees: a head on a pillow, a camera on its side) is followed in the
  // frame turned by a multiple of 45 degrees (UprightView): the turn changes
  // where the face's roll in its view passes 30 degrees, and where the frame
  // holds no face the detector sees in its view, the other turns are searched
  // too: on the first frame without a face and every 4 x fine_search_every
  // frames after (32; never where fine_search_every is 0). Where several
  // trackers share the frame's faces (FrameFaces), those say which turn each
  // face was found in, and the search that finds them paces its turns.
  bool any_roll = true;
};

struct TrackedFace {
  TrackStatus status = TrackStatus::kLost;
  Landmarks landmarks = zero_landmarks();
  Box box;                      // the box the shape predictor ran on
  int faces_seen = 0;           // faces found when the detector ran this frame (0 if it did not run)
  bool detector_ran = false;    // any detector run: the per-frame check or a full-frame search
  bool full_detection = false;  // the detector searched the whole frame (start, after a loss)
  bool fine_search = false;     // ...and again at twice the size (FaceTrackerOptions::fine_search_every)
  double detector_ms = 0;       // time spent in the HOG detector this frame
  double landmarks_ms = 0;      // time spent in the shape predictor this frame
};

class FaceTracker {
 public:
  // Where several trackers share a frame (track --all-faces), the faces its
  // whole-frame search chooses from: found once for all of them, less those
  // the others follow, each with the turn it was found in (0 for a search
  // of the frame as it is). Called only where this tracker searches.
  using FrameFaces = std::function<std::vector<TurnedFace>()>;

  FaceTracker(const LandmarkDetector& landmarks, FaceTrackerOptions options = {});

  // Landmarks for the next frame of the sequence (BGR or grey image). With
  // `frame_faces`, a search chooses among those (follow gate and pick as
  // ever) and runs no detector of its own; the per-frame check still does.
  TrackedFace next(const cv::Mat& image, const FrameFaces& frame_faces = {});
  // Forget the previous frame (the next call detects from scratch; how long
  // no face has been found, which paces the searches at twice the size, and
  // where the face was last seen are kept: the caller resets on every frame
  // it rejects, lost ones included).
  void reset();
  // A new shot (shot_cut.hpp): reset(), and where the face was last seen
  // says nothing of this shot, so FaceTrackerOptions::pick chooses again.
  void start_shot();

  // Frames since the face was last seen (0 while it is followed).
  int frames_unseen() const { return frames_unseen_; }

  // What the tracker remembers from one frame to the next: restoring it
  // takes back the frames since (FaceCapture tracks a frame while the fit of
  // the one before runs, and takes it back where that fit says reset()).
  struct Memory {
    std::optional<Landmarks> previous;
    std::optional<Box> last_seen;
    int frames_unseen = 0, frames_since_check = 0, failed_searches = 0;
    Eigen::Vector4f box_relation;
    float view_degrees = 0;
  };
  Memory memory() const {
    return {previous_, last_seen_, frames_unseen_, frames_since_check_, failed_searches_, box_relation_, view_degrees_};
  }
  void restore(const Memory& m) {
    previous_ = m.previous;
    last_seen_ = m.last_seen;
    frames_unseen_ = m.frames_unseen;
    frames_since_check_ = m.frames_since_check;
    failed_searches_ = m.failed_searches;
    box_relation_ = m.box_relation;
    view_degrees_ = m.view_degrees;
  }
  // The turn of the view the face is followed in (UprightView; 0 upright).
  float view_degrees() const { return view_degrees_; }

 private:
  // The faces a search of one view chooses from, in its coordinates.
  using ViewFaces = std::function<std::vector<FaceDetection>()>;
  // next() in the view (or frame) `grey`, its coordinates throughout; a
  // search runs the detector where `view_faces` is empty.
  TrackedFace follow(const cv::Mat& grey, const ViewFaces& view_faces);
  // Where `grey` (the frame) holds no face in the current view: faces found
  // in other turns, each taken up, the pick's choice first, as follow() takes
  // a face in its turn. The view it was taken up in goes to `found_in`;
  // `lost`, with the time added, where none was.
  TrackedFace take_up(const cv::Mat& grey, TrackedFace lost, std::vector<TurnedFace> found,
                      std::optional<UprightView>& found_in);
  // After a frame followed in `view`: a face whose roll there passes 30
  // degrees is followed in the nearest turn from the next frame on.
  void keep_upright(cv::Size frame_size, const UprightView& view, const Landmarks& lm);
  std::optional<Box> detect_face(const FaceDetector& detector, const cv::Mat& grey, int* faces_seen) const;
  // The face to take up of those a search found in the current view (the
  // follow gate, then the pick, which chooses among them as the frame shows them).
  std::optional<Box> choose_among(std::vector<FaceDetection> faces) const;
  // The same for faces in the frame's own coordinates: the index of the face
  // in `shown` to take up, or -1.
  int choose_shown(const std::vector<FaceDetection>& shown) const;
  Box box_from_landmarks(const Landmarks& lm) const;
  void learn_box_relation(const Box& detector_box, const Landmarks& lm);

  const LandmarkDetector& landmarks_;
  FaceTrackerOptions options_;
  FaceDetector detector_;
  FaceDetector fine_detector_;  // the whole frame at twice the size
  FaceDetector verifier_;
  std::optional<Landmarks> previous_;
  std::optional<Box> last_seen_;  // the landmarks' box in the last frame with the face, this shot
  int frames_unseen_ = 0;         // frames since, lost ones counted
  int frames_since_check_ = 0;
  int failed_searches_ = 0;  // whole-frame searches in a row that found no face
  // Detector box relative to the landmark bounding box: centre offset and
  // size, in units of the landmark box size (learned at each detection).
  Eigen::Vector4f box_relation_{0.0f, 0.06f, 1.0f, 0.95f};
  float view_degrees_ = 0;  // the view previous_, last_seen_ and the box relation are in
  cv::Size frame_size_;     // of the frames next() is given (the views' mapping)
};

}  // namespace facecap
