#include "facecap/detect/face_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
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
}

std::optional<Box> FaceTracker::detect_face(const FaceDetector& detector, const cv::Mat& grey, int* faces_seen) const {
  std::vector<FaceDetection> faces = detector.detect(grey);
  *faces_seen = static_cast<int>(faces.size());
  return choose_among(std::move(faces));
}

std::optional<Box> FaceTracker::choose_among(std::vector<FaceDetection> faces) const {
  if (last_seen_ && frames_unseen_ < options_.follow_frames) {
    // Lost a moment ago: the face comes back where it was, or not at all.
    const Vec2f centre = last_seen_->center();
    const float radius = options_.follow_radius * 0.5f * (last_seen_->width + last_seen_->height);
    std::erase_if(faces, [&](const FaceDetection& f) { return (f.box.center() - centre).norm() > radius; });
    if (faces.empty()) return std::nullopt;
    return choose_face(faces, {FacePick::Rule::kNearest, centre}).box;
  }
  if (faces.empty()) return std::nullopt;
  return choose_face(faces, options_.pick).box;
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

TrackedFace FaceTracker::next(const cv::Mat& image, const FrameFaces& frame_faces) {
  cv::Mat grey;
  if (image.channels() == 1) {
    grey = image;
  } else {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  }
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
  if (frame_faces) {
    std::vector<FaceDetection> faces = frame_faces();
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
