#include "facecap/pipeline/face_roster.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <span>

#include <opencv2/imgproc.hpp>

#include "facecap/core/parallel.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/detect/face_detector.hpp"
#include "facecap/pipeline/face_capture.hpp"

namespace facecap {

bool is_followed(const Box& detection, const std::vector<Box>& followed) {
  return std::any_of(followed.begin(), followed.end(), [&](const Box& f) { return same_face(detection, f); });
}

std::vector<int> match_nearest(const std::vector<Vec2f>& points, const std::vector<FaceDetection>& faces) {
  struct Pair {
    float distance;
    int point, face;
  };
  std::vector<Pair> pairs;
  for (int p = 0; p < int(points.size()); ++p)
    for (int f = 0; f < int(faces.size()); ++f) pairs.push_back({(faces[f].box.center() - points[p]).norm(), p, f});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.distance != b.distance ? a.distance < b.distance
                                    : (a.point != b.point ? a.point < b.point : a.face < b.face);
  });
  std::vector<int> match(points.size(), -1);
  std::vector<bool> used(faces.size(), false);
  for (const Pair& pair : pairs) {
    if (match[pair.point] >= 0 || used[pair.face]) continue;
    match[pair.point] = pair.face;
    used[pair.face] = true;
  }
  return match;
}

namespace {

struct Slot {
  FoundFace face;
  std::unique_ptr<FaceCapture> capture;
  std::optional<Box> box;  // the landmarks' box in the last frame it was followed
  // The faces' captures run in parallel; their frames wait here and reach
  // their sinks in order, on the loop's thread.
  std::vector<CapturedFrame> pending;
  FrameSink sink;
  std::exception_ptr error;

  void flush() {
    for (const CapturedFrame& f : pending) sink(f);
    pending.clear();
  }
};

// The face of `box` in `image`: a square 1.6 times the box, clipped to the
// image, scaled to FoundFace::kThumbnailSize (black where the input gave no image).
cv::Mat face_thumbnail(const cv::Mat& image, const Box& box) {
  const int size = FoundFace::kThumbnailSize;
  cv::Mat thumbnail(size, size, CV_8UC3, cv::Scalar::all(0));
  if (image.empty()) return thumbnail;
  const float side = 1.6f * std::max(box.width, box.height);
  const cv::Rect want(cvRound(box.center().x() - side / 2), cvRound(box.center().y() - side / 2), cvRound(side),
                      cvRound(side));
  const cv::Rect have = want & cv::Rect(0, 0, image.cols, image.rows);
  if (have.area() <= 0) return thumbnail;
  // Where the clipped part lands in the square, at the square's scale.
  const double scale = double(size) / want.width;
  const cv::Rect at(cvRound((have.x - want.x) * scale), cvRound((have.y - want.y) * scale),
                    std::max(1, cvRound(have.width * scale)), std::max(1, cvRound(have.height * scale)));
  const cv::Rect inside = at & cv::Rect(0, 0, size, size);
  cv::Mat scaled;
  cv::resize(image(have), scaled, at.size(), 0, 0, cv::INTER_AREA);
  scaled(cv::Rect(0, 0, inside.width, inside.height)).copyTo(thumbnail(inside));
  return thumbnail;
}

// Faces found in the frame as it is.
std::vector<TurnedFace> upright(const std::vector<FaceDetection>& faces) {
  std::vector<TurnedFace> out;
  for (const FaceDetection& f : faces) out.push_back({0, f, f});
  return out;
}

// Merges another search (at twice the size, or of turned views) into the
// faces found so far: its faces that are not already there.
void add_new_faces(std::vector<TurnedFace>& faces, const std::vector<TurnedFace>& more) {
  std::vector<Box> have;
  for (const TurnedFace& f : faces) have.push_back(f.shown.box);
  for (const TurnedFace& f : more)
    if (!is_followed(f.shown.box, have)) faces.push_back(f);
}

}  // namespace

AllFacesSummary run_capture_all_faces(const FaceModel& model, FrameSource& source, CaptureOptions options,
                                      const AllFacesOptions& all, const NewFaceSink& on_new_face,
                                      const FrameFacesHook& on_frame) {
  options.check();
  const auto start = std::chrono::steady_clock::now();
  AllFacesSummary summary;
  summary.input = source.info();
  if (summary.input.kind == InputKind::kImage) options.fit.set_single_image();
  // A capture searches every frame for a face it lost a moment ago (as one
  // face's capture does), and otherwise only where the roster searches.
  const int recent_frames = options.tracker.follow_frames;
  const LandmarkDetector landmark_detector;
  const FaceDetector detector(options.tracker.detector), fine_detector(twice_the_size(options.tracker.detector));
  std::vector<std::unique_ptr<Slot>> slots;
  StageTimings& t = summary.timings;
  t.setup_ms = ms_since(start);
  int searches = 0;
  size_t turn_searches = 0;
  int shot = 0;

  // Faces no capture follows start their own, left to right.
  auto start_new_faces = [&](const DecodedFrame& d, std::vector<TurnedFace> fresh) {
    std::vector<Box> followed;
    for (const auto& s : slots)
      if (s->box) followed.push_back(*s->box);
    std::erase_if(fresh, [&](const TurnedFace& f) { return is_followed(f.shown.box, followed); });
    std::sort(fresh.begin(), fresh.end(), [](const TurnedFace& a, const TurnedFace& b) {
      return a.shown.box.center().x() < b.shown.box.center().x();
    });
    int uncaptured = 0;
    for (const TurnedFace& f : fresh) {
      if (is_followed(f.shown.box, followed)) continue;  // one started just now has it
      if (int(slots.size()) >= all.max_faces) {
        summary.uncaptured_faces = std::max(summary.uncaptured_faces, ++uncaptured);
        continue;
      }
      Slot& slot = *slots.emplace_back(std::make_unique<Slot>());
      // The thumbnail shows the face upright, as its turn does.
      const bool turned = f.degrees != 0 && !d.frame.image.empty();
      slot.face = {int(slots.size()) - 1,
                   d.frame.index,
                   d.frame.time,
                   f.shown.box,
                   shot,
                   turned ? face_thumbnail(UprightView(d.frame.image, f.degrees).image(), f.in_view.box)
                          : face_thumbnail(d.frame.image, f.shown.box)};
      InputInfo info = summary.input;
      info.first_frame = d.frame.index;
      info.first_time = d.frame.time;
      CaptureOptions own = options;
      own.tracker.pick = {FacePick::Rule::kNearest, f.shown.box.center()};
      own.tracker.follow_frames = INT_MAX;  // never another face elsewhere: that one is a capture of its own
      slot.sink = on_new_face(slot.face, info);
      slot.capture = std::make_unique<FaceCapture>(
          model, landmark_detector, own, info, [&slot](const CapturedFrame& f) { slot.pending.push_back(f); }, shot);
      slot.capture->set_pipelined(false);  // its first frame is tracked with the others' done
      const TrackedFace& tracked = slot.capture->push(d, false, [&f] { return std::vector<TurnedFace>{f}; });
      if (tracked.status != TrackStatus::kLost) slot.box = bounding_box(tracked.landmarks);
      slot.flush();
      followed.push_back(slot.box.value_or(f.shown.box));
    }
  };

  const FrameLoopResult loop = run_frame_loop(source, options, [&](const DecodedFrame& d, bool cut) {
    shot += cut;
    const bool shot_start = d.frame.index == summary.input.first_frame || cut;
    const bool search_frame = shot_start || (d.frame.index - summary.input.first_frame) % all.search_every == 0;
    // This frame's faces, found once, where a capture or the roster first
    // asks (on a search frame, the roster always does): upright (at twice
    // the size every fine_every-th search, or where there are none), and
    // with tracker.any_roll in turned views of the frame: the turns the
    // captures follow their faces in, all seven at the first frame and at
    // cuts (and where no view shows a face, the half turns between them),
    // and one more, in turn, every fine_every-th search (each turn every
    // 7 x 32 frames: all seven each time took 5 ms a frame on average, at
    // 1280x720, of a video of upright faces, 85 -> 59 fps).
    const bool paced = search_frame && searches++ % all.fine_every == 0;
    std::vector<float> turns;
    auto search_turn = [&turns](float degrees) {
      if (degrees != 0 && std::find(turns.begin(), turns.end(), degrees) == turns.end()) turns.push_back(degrees);
    };
    if (options.tracker.any_roll) {
      for (const auto& s : slots) search_turn(s->capture->face_tracker().view_degrees());
      if (shot_start) {
        for (const float degrees : kFaceTurns) search_turn(degrees);
      } else if (paced) {
        search_turn(kFaceTurns[1 + turn_searches++ % (kFaceTurns.size() - 1)]);
      }
    }
    std::vector<TurnedFace> found;
    std::once_flag found_once;
    auto frame_faces = [&]() -> const std::vector<TurnedFace>& {
      std::call_once(found_once, [&] {
        const auto t0 = std::chrono::steady_clock::now();
        if (!d.grey.empty()) {
          found = upright(detector.detect(d.grey));
          if (paced || (search_frame && found.empty())) add_new_faces(found, upright(fine_detector.detect(d.grey)));
          // At a shot's start with no face upright, as the tracker's first search.
          const bool first = options.tracker.any_roll && shot_start && found.empty();
          const auto search = first ? find_first_turned_faces : find_turned_faces;
          add_new_faces(found, search(detector, d.grey, turns, options.tracker.detector.max_side, nullptr));
        }
        t.detect_ms += ms_since(t0);
      });
      return found;
    };
    // After a cut, the new shot's faces go to the captures whose faces first
    // appeared nearest them.
    std::vector<int> assigned(slots.size(), -1);
    if (cut && !slots.empty()) {
      std::vector<Vec2f> homes;
      for (const auto& s : slots) homes.push_back(s->face.box.center());
      std::vector<FaceDetection> shown;
      for (const TurnedFace& f : frame_faces()) shown.push_back(f.shown);
      assigned = match_nearest(homes, shown);
    }
    // Where the faces were in the last frame: a capture searching for its
    // face takes none of the others'.
    std::vector<std::optional<Box>> last_boxes;
    for (const auto& s : slots) last_boxes.push_back(s->box);
    auto others = [&](size_t k) {
      std::vector<Box> boxes;
      for (size_t j = 0; j < last_boxes.size(); ++j)
        if (j != k && last_boxes[j]) boxes.push_back(*last_boxes[j]);
      return boxes;
    };
    // Each face's landmarks and fit, in parallel (one face's work does not
    // depend on another's in this frame); a face alone is pipelined instead.
    for (const auto& s : slots) s->capture->set_pipelined(options.pipelined && slots.size() == 1);
    parallel_for(
        int(slots.size()),
        [&](int begin, int end) {
          for (int k = begin; k < end; ++k) {
            Slot& slot = *slots[k];
            const FaceTracker::FrameFaces choices = [&, k]() -> std::vector<TurnedFace> {
              if (cut)
                return assigned[k] >= 0 ? std::vector<TurnedFace>{frame_faces()[assigned[k]]}
                                        : std::vector<TurnedFace>{};
              if (!search_frame && slot.capture->face_tracker().frames_unseen() >= recent_frames) return {};
              std::vector<TurnedFace> faces = frame_faces();
              const std::vector<Box> taken = others(k);
              std::erase_if(faces, [&](const TurnedFace& f) { return is_followed(f.shown.box, taken); });
              return faces;
            };
            try {
              const TrackedFace& tracked = slot.capture->push(d, cut, choices);
              slot.box.reset();
              if (tracked.status != TrackStatus::kLost) slot.box = bounding_box(tracked.landmarks);
            } catch (...) {
              slot.error = std::current_exception();
            }
          }
        },
        1);
    for (const auto& slot : slots) {
      if (slot->error) std::rethrow_exception(slot->error);
      slot->flush();
    }
    if (search_frame) start_new_faces(d, frame_faces());
    if (on_frame) on_frame(d, int(slots.size()));
  });
  for (const auto& slot : slots) {
    summary.faces.push_back(slot->face);
    summary.captures.push_back(slot->capture->finish());
    slot->flush();
  }
  summary.cuts = loop.cuts;
  summary.damage = loop.damage;
  summary.stopped_by_user = loop.stopped_by_user;
  t.decode_ms = loop.decode_ms;
  t.frames = loop.frames;
  t.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace facecap
