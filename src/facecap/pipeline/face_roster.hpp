#pragma once
// Every face an input shows, each captured on its own (FaceCapture) from the
// frame it is first found in, on one decoding pass (`track --all-faces`).
//
// The whole frame is searched for faces at the first frame, every
// AllFacesOptions::search_every frames and at each shot cut (also turned by
// multiples of 45 degrees, for faces at any roll: turned_faces.hpp); a face
// that no capture follows there starts a capture of its own. The searches are shared:
// a capture that lost its face chooses among their faces, less those the
// others follow, and takes up only a face where its own was last seen, so
// that it is never fitted with another person's identity. A face that comes
// back elsewhere counts as a new one. After a shot cut, the faces of the new
// shot go to the captures whose faces first appeared nearest them (each
// shot's identity is solved afresh), and the rest start captures of their own.
#include <functional>
#include <set>
#include <vector>

#include <opencv2/core.hpp>

#include "facecap/pipeline/capture_session.hpp"
#include "facecap/pipeline/frame_loop.hpp"

namespace facecap {

struct AllFacesOptions {
  int search_every = 8;  // frames between whole-frame searches for new faces
  int fine_every = 4;    // every this many searches, also at twice the size (faces down to half as small)
  int max_faces = 8;     // faces past this many are not captured (AllFacesSummary::uncaptured_faces)
  // For the edits (transform and swap --all-faces): faces, by FoundFace::index,
  // that are followed but left as they are (`--leave-faces`: say, the one
  // person in a crowd who is not to be anonymised).
  std::set<int> unedited;
};

struct FoundFace {
  int index = 0;        // in the order found (left to right among those found together)
  int first_frame = 0;  // the input's frame it was first found in
  double first_time = 0;
  Box box;            // the detector's box there
  int shot = 0;       // the input's shot there
  cv::Mat thumbnail;  // the face there, 1.6 times its box, kThumbnailSize pixels square (BGR)
  static constexpr int kThumbnailSize = 128;
};

// Called once per face as it is found: the sink that takes its frames, from
// first_frame on. `info` is the input as that face's capture sees it (its
// first frame and time are the face's).
using NewFaceSink = std::function<FrameSink(const FoundFace& face, const InputInfo& info)>;

struct AllFacesSummary {
  std::vector<FoundFace> faces;
  std::vector<CaptureSummary> captures;  // one per face, in that order
  // The shared work: decoding, the whole-frame searches (detect_ms), setup
  // and the run's wall time.
  StageTimings timings;
  int cuts = 0;
  InputDamage damage;  // what a corrupt input cost
  bool stopped_by_user = false;
  int uncaptured_faces = 0;  // the most faces one search found past AllFacesOptions::max_faces
  InputInfo input;
};

// Called once per frame, in order, after the frame went to its faces'
// captures (those found in it included): `faces`, the captures there are,
// each of which delivers this frame to its sink (now or once its fit is final).
using FrameFacesHook = std::function<void(const DecodedFrame& frame, int faces)>;

AllFacesSummary run_capture_all_faces(const FaceModel& model, FrameSource& source, CaptureOptions options,
                                      const AllFacesOptions& all, const NewFaceSink& on_new_face,
                                      const FrameFacesHook& on_frame = {});

// Whether the face `detection` is one of `followed` (a face's landmark box):
// its centre within half that face's size of the followed face's centre.
bool is_followed(const Box& detection, const std::vector<Box>& followed);

// Greedy matching of faces to points, nearest pairs first: for each point,
// the index of its face in `faces`, or -1.
std::vector<int> match_nearest(const std::vector<Vec2f>& points, const std::vector<FaceDetection>& faces);

}  // namespace facecap
