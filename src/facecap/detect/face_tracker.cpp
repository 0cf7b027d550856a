#include "facecap/detect/face_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <opencv2/imgproc.hpp>
#include <string>

#include "facecap/core/error.hpp"
#include "facecap/core/stopwatch.hpp"

namespace facecap {

float box_overlap(const Box& a, const Box& b) {
  const float x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const float x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
  const float inter = std::max(0.0f, x1 - x0) * std::max(0.0f, y1 - y0);
  const float uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0f;
}

const char* to_string(TrackStatus status) {
  switch (status) {
    case TrackStatus::kTracked:
      return "tracked";
    case TrackStatus::kRedetected:
      return "redetected";
    case TrackStatus::kLost:
      return "lost";
  }
  return "lost";
}

FacePick parse_face_pick(std::string_view text) {
  FacePick pick;
  if (text == "largest") return pick;
  if (text == "left" || text == "right") {
    pick.rule = text == "left" ? FacePick::Rule::kLeftmost : FacePick::Rule::kRightmost;
    return pick;
  }
  const std::string s(text);
  float x = 0, y = 0;
  int used = 0;
  if (std::sscanf(s.c_str(), "%f,%f%n", &x, &y, &used) == 2 && used == int(s.size()) && std::isfinite(x) &&
      std::isfinite(y)) {
    pick.rule = FacePick::Rule::kNearest;
    pick.point = {x, y};
    return pick;
  }
  throw Error("must be largest, left, right or X,Y (pixels), not '" + s + "'");
}

std::string describe(const FacePick& pick) {
  switch (pick.rule) {
    case FacePick::Rule::kLeftmost:
      return "leftmost";
    case FacePick::Rule::kRightmost:
      return "rightmost";
    case FacePick::Rule::kNearest: {
      char text[64];
      std::snprintf(text, sizeof(text), "one nearest (%g, %g)", pick.point.x(), pick.point.y());
      return text;
    }
    case FacePick::Rule::kLargest:
      break;
  }
  return "largest";
}

const FaceDetection& choose_face(const std::vector<FaceDetection>& faces, const FacePick& pick) {
  auto by = [&](auto key) -> const FaceDetection& {
    return *std::min_element(faces.begin(), faces.end(),
                             [&](const FaceDetection& a, const FaceDetection& b) { return key(a) < key(b); });
  };
  switch (pick.rule) {
    case FacePick::Rule::kLeftmost:
      return by([](const FaceDetection& f) { return f.box.center().x(); });
    case FacePick::Rule::kRightmost:
      return by([](const FaceDetection& f) { return -f.box.center().x(); });
    case FacePick::Rule::kNearest:
      return by([&](const FaceDetection& f) { return (f.box.center() - pick.point).squaredNorm(); });
    case FacePick::Rule::kLargest:
      break;
  }
  return by([](const FaceDetection& f) { return -f.box.area(); });
}

FaceTracker::FaceTracker(const LandmarkDetector& landmarks, FaceTrackerOptions options)
    : landmarks_(landmarks),
      options_(options),
      detector_(options.detector),
      fine_detector_(twice_the_size(options.detector)),
      // The check runs on a crop 1.6 times the face, scaled (down or up) so
      // that the face is about 80-90 px, just above the detector's window: a
      // pyramid of two or three levels. A slightly lowered threshold keeps
      // turned heads.
      verifier_(FaceDetectorOptions{.max_side = 130, .min_side = 130, .upsample = 0, .adjust_threshold = -0.4}) {}

void FaceTracker::reset() {
  previous_.reset();
  frames_since_check_ = 0;
}

void FaceTracker::start_shot() {
  reset();
  last_seen_.reset();
  view_degrees_ = 0;  // most shots start upright
}

std::optional<Box> FaceTracker::detect_face(const FaceDetector& detector, const cv::Mat& grey, int* faces_seen) const {
  std::vector<FaceDetection> faces = detector.detect(grey);
  *faces_seen = static_cast<int>(faces.size());
  return choose_among(std::move(faces));
}

int FaceTracker::choose_shown(const std::vector<FaceDetection>& shown) const {
  if (shown.empty()) return -1;
  if (last_seen_ && frames_unseen_ < options_.follow_frames) {
    // Lost a moment ago: the face comes back where it was, or not at all.
    const Box seen = carried(*last_seen_, UprightView(frame_size_, view_degrees_), UprightView(frame_size_, 0));
    const float radius = options_.follow_radius * 0.5f * (seen.width + seen.height);
    std::vector<FaceDetection> near;
    std::vector<int> index;
    for (int i = 0; i < int(shown.size()); ++i) {
      if ((shown[i].box.center() - seen.center()).norm() > radius) continue;
      near.push_back(shown[i]);
      index.push_back(i);
    }
    if (near.empty()) return -1;
    return index[&choose_face(near, {FacePick::Rule::kNearest, seen.center()}) - near.data()];
  }
  return static_cast<int>(&choose_face(shown, options_.pick) - shown.data());
}

std::optional<Box> FaceTracker::choose_among(std::vector<FaceDetection> faces) const {
  // The pick's point, and left and right, are the frame's as shown.
  const UprightView view(frame_size_, view_degrees_), frame(frame_size_, 0);
  std::vector<FaceDetection> shown = faces;
  for (FaceDetection& f : shown) f.box = carried(f.box, view, frame);
  const int chosen = choose_shown(shown);
  if (chosen < 0) return std::nullopt;
  return faces[chosen].box;
}

Box FaceTracker::box_from_landmarks(const Landmarks& lm) const {
  const Box b = bounding_box(lm);
  const float size = 0.5f * (b.width + b.height);
  const Vec2f c = b.center() + Vec2f(box_relation_[0], box_relation_[1]) * size;
  const float w = box_relation_[2] * size;
  const float h = box_relation_[3] * size;
  return {c.x() - 0.5f * w, c.y() - 0.5f * h, w, h};
}

void FaceTracker::learn_box_relation(const Box& det, const Landmarks& lm) {
  const Box b = bounding_box(lm);
  const float size = 0.5f * (b.width + b.height);
  if (size < 1.0f) return;
  const Vec2f offset = (det.center() - b.center()) / size;
  const Eigen::Vector4f measured(offset.x(), offset.y(), det.width / size, det.height / size);
  box_relation_ = 0.7f * box_relation_ + 0.3f * measured;
}

namespace {

// A face's roll in its view past which it is followed in the next turn:
// within the detector's and the cascade's reach, and far enough from the
// 22.5 degrees where the next turn would take it back.
constexpr float kTurnAt = 30;
constexpr int kTurnedSearchPace = 4;

// A turn in (-180, 180].
float wrapped(float degrees) {
  while (degrees > 180) degrees -= 360;
  while (degrees <= -180) degrees += 360;
  return degrees;
}

TrackedFace in_frame(TrackedFace out, const UprightView& view) {
  if (out.status == TrackStatus::kLost) return out;
  out.landmarks = view.to_frame(out.landmarks);
  out.box = view.to_frame(out.box);
  return out;
}

}  // namespace

TrackedFace FaceTracker::next(const cv::Mat& image, const FrameFaces& frame_faces) {
  cv::Mat grey;
  if (image.channels() == 1) {
    grey = image;
  } else {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  }
  frame_size_ = grey.size();
  if (!options_.any_roll) view_degrees_ = 0;
  // The shared faces, asked for once; those found in the current view are
  // that view's search.
  std::optional<std::vector<TurnedFace>> shared;
  auto shared_faces = [&]() -> const std::vector<TurnedFace>& {
    if (!shared) shared = frame_faces();
    return *shared;
  };
  auto in_turn = [&](float degrees) -> ViewFaces {
    if (!frame_faces) return {};
    return [&, degrees] {
      std::vector<FaceDetection> faces;
      for (const TurnedFace& f : shared_faces())
        if (f.degrees == degrees) faces.push_back(f.in_view);
      return faces;
    };
  };
  const UprightView view(grey, view_degrees_);
  TrackedFace out = follow(view.image(), in_turn(view_degrees_));
  if (!options_.any_roll) return out;
  if (out.status != TrackStatus::kLost) {
    keep_upright(grey.size(), view, *previous_);
    return in_frame(out, view);
  }
  std::vector<TurnedFace> turned;
  if (frame_faces) {
    std::copy_if(shared_faces().begin(), shared_faces().end(), std::back_inserter(turned),
                 [&](const TurnedFace& f) { return f.degrees != view_degrees_; });
  } else {
    // The other turns on the first frame without a face and every
    // kTurnedSearchPace-th search at twice the size after it (at 1280x720
    // the seven turns take some 150 ms: every 8th frame, a video without a
    // face went from 46 to 25 fps; every 32nd, 39). Every other turn is
    // searched, so that the pick chooses among all the faces the frame
    // shows, however they are turned.
    if (!out.fine_search || (failed_searches_ - 1) % (kTurnedSearchPace * options_.fine_search_every) != 0) return out;
    std::vector<float> turns;
    std::copy_if(kFaceTurns.begin(), kFaceTurns.end(), std::back_inserter(turns),
                 [&](float degrees) { return degrees != view_degrees_; });
    // In the shot's first search, before any face was seen, also the views
    // halfway between them where none finds a face (about 0.15 s more at
    // 1280x720, once).
    const bool first_search = !last_seen_ && failed_searches_ == 1;
    turned = (first_search ? find_first_turned_faces : find_turned_faces)(detector_, grey, turns,
                                                                          options_.detector.max_side, &out.detector_ms);
  }
  std::optional<UprightView> found_in;
  out = take_up(grey, out, std::move(turned), found_in);
  if (!found_in) return out;
  // The detector reaches about 45 degrees from upright, where the cascade's
  // landmarks are rough (the LFPW portrait turned 90 degrees, found in the
  // turn 45 degrees off: NME 0.11): followed again, this frame, in the turn
  // nearest its roll (with shared faces, without a search of its own).
  const Memory found = memory();
  keep_upright(grey.size(), *found_in, *previous_);
  if (view_degrees_ == found.view_degrees) return in_frame(out, *found_in);
  const UprightView nearer(grey, view_degrees_);
  const ViewFaces no_faces = [] { return std::vector<FaceDetection>{}; };
  TrackedFace again = follow(nearer.image(), frame_faces ? no_faces : ViewFaces{});
  if (again.status == TrackStatus::kLost) {
    restore(found);
    return in_frame(out, *found_in);
  }
  again.status = TrackStatus::kRedetected;
  again.detector_ms += out.detector_ms;
  again.landmarks_ms += out.landmarks_ms;
  again.faces_seen = std::max(again.faces_seen, out.faces_seen);
  again.detector_ran = again.full_detection = again.fine_search = true;
  keep_upright(grey.size(), nearer, *previous_);
  return in_frame(again, nearer);
}

TrackedFace FaceTracker::take_up(const cv::Mat& grey, TrackedFace lost, std::vector<TurnedFace> found,
                                 std::optional<UprightView>& found_in) {
  const int seen = static_cast<int>(found.size());
  // Taken up as a search in its view takes a face (the follow gate: where
  // it was last seen, turned into the view), the pick's choice first.
  while (!found.empty()) {
    std::vector<FaceDetection> shown;
    for (const TurnedFace& f : found) shown.push_back(f.shown);
    const int chosen = choose_shown(shown);
    if (chosen < 0) break;
    const TurnedFace face = found[chosen];
    found.erase(found.begin() + chosen);
    const Memory before = memory();
    const UprightView full_size(grey, face.degrees);
    if (last_seen_) last_seen_ = carried(*last_seen_, UprightView(grey.size(), view_degrees_), full_size);
    view_degrees_ = face.degrees;
    TrackedFace out = follow(full_size.image(), [&] { return std::vector<FaceDetection>{face.in_view}; });
    if (out.status == TrackStatus::kLost) {
      restore(before);
      continue;
    }
    out.detector_ms += lost.detector_ms;
    out.landmarks_ms += lost.landmarks_ms;
    out.faces_seen = std::max(out.faces_seen, seen);
    out.detector_ran = out.full_detection = out.fine_search = true;
    found_in.emplace(full_size);
    return out;
  }
  return lost;
}

void FaceTracker::keep_upright(cv::Size frame_size, const UprightView& view, const Landmarks& lm) {
  const float roll = roll_degrees(lm);
  if (std::abs(roll) <= kTurnAt) return;
  const float degrees = wrapped(view_degrees_ + 45.0f * std::round(roll / 45.0f));
  const UprightView next(frame_size, degrees);
  previous_ = next.to_view(view.to_frame(lm));
  last_seen_ = bounding_box(*previous_);
  view_degrees_ = degrees;
}

TrackedFace FaceTracker::follow(const cv::Mat& grey, const ViewFaces& view_faces) {
  TrackedFace out;

  // How much larger the face `lm` is than `reference` (the square root of their areas' ratio).
  auto scale_of = [](const Landmarks& lm, const Box& reference) {
    return std::sqrt(std::max(1.0f, bounding_box(lm).area()) / std::max(1.0f, reference.area()));
  };
  auto plausible = [&](const Landmarks& lm, const Box& reference) {
    if (outer_eye_distance(lm) < options_.min_eye_distance) return false;
    const Vec2f c = bounding_box(lm).center();
    if (c.x() < 0 || c.y() < 0 || c.x() >= grey.cols || c.y() >= grey.rows) return false;
    const float s = scale_of(lm, reference);
    return s < options_.max_scale_change && s > 1.0f / options_.max_scale_change;
  };
  // Whether `lm` is a face much smaller than `reference`: what the detector
  // finds of a turned face it no longer sees whole (its lowered threshold in
  // the per-frame check, or a whole-frame search) is its nose and mouth, a
  // face two thirds the size whose landmarks the fit would follow away (a
  // render turned 25 degrees: 16 frames at 1.4-1.8 times the distance).
  auto part_of = [&](const Landmarks& lm, const Box& reference) {
    return scale_of(lm, reference) < 1.0f / options_.max_scale_change;
  };
  // The tracked landmarks of a frame whose check found no face, and the box
  // they were found on: kept where a search finds only part of it.
  std::optional<Landmarks> unconfirmed;
  Box unconfirmed_box;
  // The frame's face, followed from here on. The tracker follows the face
  // with one pass of the cascade (`lm`, found on `ran_on`); the landmarks it
  // hands out are the mean of that pass and the mirror image's on the same
  // box (LandmarkDetector::detect). Followed by the mean, the check's
  // borderline decisions on a face turned 20-30 degrees came out otherwise:
  // a render of seed 3 lost a frame and was then boxed on its nose and mouth
  // (CaptureSession.ATurnedFaceIsNotTakenForTheDetectorsPartOfIt).
  auto take = [&](TrackStatus status, const Landmarks& lm, const Box& box, const Box& ran_on) {
    out.status = status;
    if (options_.mirror_average) {
      const auto t0 = std::chrono::steady_clock::now();
      out.landmarks = landmarks_.average_with_mirror(grey, ran_on, lm);
      out.landmarks_ms += ms_since(t0);
    } else {
      out.landmarks = lm;
    }
    out.box = box;
    previous_ = lm;
    last_seen_ = bounding_box(lm);
    frames_unseen_ = 0;
    return out;
  };

  if (previous_) {
    const Box box = box_from_landmarks(*previous_);
    auto t0 = std::chrono::steady_clock::now();
    Landmarks lm = landmarks_.detect_once(grey, box);
    out.landmarks_ms += ms_since(t0);
    Box used = box;
    bool ok = plausible(lm, bounding_box(*previous_));
    bool reanchored = false;
    if (ok && options_.verify_every > 0 && ++frames_since_check_ >= options_.verify_every) {
      frames_since_check_ = 0;
      const Box b = box_from_landmarks(lm);
      const Box crop{b.center().x() - 0.8f * b.width, b.center().y() - 0.8f * b.height, 1.6f * b.width,
                     1.6f * b.height};
      t0 = std::chrono::steady_clock::now();
      const auto faces = verifier_.detect_in(grey, crop);
      out.detector_ms += ms_since(t0);
      out.detector_ran = true;
      out.faces_seen = static_cast<int>(faces.size());
      ok = !faces.empty();
      if (ok) {
        // The shape predictor was trained on detector boxes: when the box
        // implied by the tracked landmarks has drifted from the detector's,
        // re-anchor on the detector's box.
        // Of the faces in the crop (two heads close together), the one the
        // landmarks are on.
        const Box tracked = box_from_landmarks(lm);
        const Box& det =
            std::max_element(faces.begin(), faces.end(), [&](const FaceDetection& a, const FaceDetection& b) {
              return box_overlap(a.box, tracked) < box_overlap(b.box, tracked);
            })->box;
        bool part = false;
        if (box_overlap(det, tracked) < options_.min_box_overlap) {
          t0 = std::chrono::steady_clock::now();
          const Landmarks anchored = landmarks_.detect_once(grey, det);
          out.landmarks_ms += ms_since(t0);
          part = part_of(anchored, bounding_box(*previous_));
          if (!part) {
            lm = anchored;
            used = det;
            reanchored = true;
          }
        }
        if (!part) learn_box_relation(det, lm);
      } else {
        unconfirmed = lm;
        unconfirmed_box = box;
      }
    }
    if (ok) return take(reanchored ? TrackStatus::kRedetected : TrackStatus::kTracked, lm, used, used);
    previous_.reset();
  }

  int faces_seen = 0;
  std::optional<Box> box;
  if (view_faces) {
    std::vector<FaceDetection> faces = view_faces();
    faces_seen = static_cast<int>(faces.size());
    box = choose_among(std::move(faces));
  } else {
    auto t0 = std::chrono::steady_clock::now();
    box = detect_face(detector_, grey, &faces_seen);
    if (!box && options_.fine_search_every > 0 && failed_searches_ % options_.fine_search_every == 0) {
      box = detect_face(fine_detector_, grey, &faces_seen);
      out.fine_search = true;
    }
    out.detector_ms += ms_since(t0);
    out.detector_ran = true;
    out.full_detection = true;
  }
  out.faces_seen = faces_seen;
  if (!box) {
    ++failed_searches_;
    ++frames_unseen_;
    out.status = TrackStatus::kLost;
    return out;
  }
  failed_searches_ = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const Landmarks lm = landmarks_.detect_once(grey, *box);
  out.landmarks_ms += ms_since(t0);
  // The check missed a face the search finds only part of: it is still there.
  if (unconfirmed && part_of(lm, bounding_box(*unconfirmed)))
    return take(TrackStatus::kTracked, *unconfirmed, box_from_landmarks(*unconfirmed), unconfirmed_box);
  learn_box_relation(*box, lm);
  frames_since_check_ = 0;
  return take(TrackStatus::kRedetected, lm, *box, *box);
}

}  // namespace facecap
