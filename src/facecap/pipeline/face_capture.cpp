#include "facecap/pipeline/face_capture.hpp"

#include <algorithm>
#include <chrono>

#include "facecap/core/stopwatch.hpp"

namespace facecap {

FaceCapture::FaceCapture(const FaceModel& model, const LandmarkDetector& landmarks, const CaptureOptions& options,
                         const InputInfo& info, FrameSink sink, int shot)
    : options_(options),
      face_tracker_(landmarks, options.tracker),
      tracker_(model, options.fit, info.width, info.height),
      sink_(std::move(sink)),
      shot_(shot),
      shot_start_(info.first_frame) {
  summary_.input = info;
}

void FaceCapture::deliver(const std::vector<CoarseFit>& fits) {
  for (const CoarseFit& fit : fits) {
    auto it = waiting_.find(fit.index);
    CapturedFrame out;
    out.index = fit.index;
    out.time = fit.time;
    out.fit = fit;
    out.status = fit.valid ? it->second.status : TrackStatus::kLost;
    out.faces_seen = it->second.faces_seen;
    out.image = it->second.image;
    out.error = it->second.error;
    out.damaged = it->second.damaged;
    out.identity = tracker_.identity();
    out.shot = it->second.shot;
    waiting_.erase(it);
    summary_.lost += out.status == TrackStatus::kLost;
    summary_.redetected += out.status == TrackStatus::kRedetected;
    summary_.most_faces = std::max(summary_.most_faces, out.faces_seen);
    if (!out.error.empty() && summary_.unreadable++ == 0) summary_.first_error = out.error;
    ++summary_.frames;
    sink_(out);
  }
}

// The tracker's output, timed: its identity solves (one a shot) apart from
// the per-frame fits.
std::vector<CoarseFit> FaceCapture::timed(const std::function<std::vector<CoarseFit>()>& call) {
  StageTimings& t = summary_.timings;
  const bool was_initialized = tracker_.initialized();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<CoarseFit> fits = call();
  t.fit_ms += ms_since(t0);
  if (!was_initialized && tracker_.initialized()) {
    t.identity_ms += tracker_.identity().solve_ms;
    t.fit_ms -= tracker_.identity().solve_ms;
  }
  return fits;
}

// A shot ends: its frames still waiting are fitted with what it showed, and
// its identity is kept.
void FaceCapture::end_shot() {
  deliver(timed([&] { return tracker_.finish(); }));
  if (tracker_.initialized()) summary_.shots.push_back({shot_, shot_start_, tracker_.identity()});
}

FaceCapture::FitJob FaceCapture::track(const DecodedFrame& d, const FaceTracker::FrameFaces& frame_faces) {
  const Frame& frame = d.frame;
  StageTimings& t = summary_.timings;
  last_ = TrackedFace{};
  if (!d.grey.empty()) last_ = face_tracker_.next(d.grey, frame_faces);
  t.detect_ms += last_.detector_ms;
  t.landmarks_ms += last_.landmarks_ms;

  FitJob job{frame.index, frame.time, std::nullopt, {}};
  if (last_.status != TrackStatus::kLost) job.landmarks = last_.landmarks;
  cv::Mat kept;
  if (options_.keep_images) kept = image_or_black(frame, summary_.input);
  waiting_[frame.index] = {last_.status, last_.faces_seen, kept, frame.error, frame.damaged, shot_};
  if (job.landmarks && options_.gaze) {
    // Timed where the tracker calls it (maybe later, after the identity solve).
    job.iris_search = [search = facecap::iris_search(d.grey, *job.landmarks),
                       &t](const std::array<IrisExpectation, 2>& expected) {
      const auto t0 = std::chrono::steady_clock::now();
      IrisPair irises = search(expected);
      t.iris_ms += ms_since(t0);
      return irises;
    };
  }
  return job;
}

FaceCapture::FitResult FaceCapture::fit(FitJob job) {
  FitResult result;
  result.fits = timed([&] { return tracker_.push(job.index, job.time, job.landmarks, std::move(job.iris_search)); });
  // A fit that rejects the landmarks means the box tracker followed
  // something that is not the face: detect afresh on the next frame.
  result.rejected = tracker_.last_rejected() == job.index;
  summary_.rejected += result.rejected;
  return result;
}

bool FaceCapture::finish_pending_fit() {
  if (!pending_.valid()) return false;
  const FitResult result = pending_.get();
  if (result.rejected) face_tracker_.reset();
  deliver(result.fits);
  return result.rejected;
}

const TrackedFace& FaceCapture::push(const DecodedFrame& d, bool cut, const FaceTracker::FrameFaces& frame_faces) {
  if (cut) {
    finish_pending_fit();
    end_shot();
    tracker_.start_shot();
    face_tracker_.start_shot();  // the last shot's box says nothing of this one
    ++shot_;
    shot_start_ = d.frame.index;
    ++summary_.cuts;
  }
  ++summary_.timings.frames;
  if (!options_.pipelined) {
    finish_pending_fit();  // pipelined until this frame
    const FitResult result = fit(track(d, frame_faces));
    if (result.rejected) face_tracker_.reset();
    deliver(result.fits);
    return last_;
  }
  // This frame's landmarks while the last frame's fit runs; where that fit
  // rejects its frame, the tracker should have been reset before this one:
  // this frame is taken back and tracked again from there.
  const FaceTracker::Memory before = face_tracker_.memory();
  FitJob job = track(d, frame_faces);
  if (finish_pending_fit()) {
    face_tracker_.restore(before);  // as it was before this frame, then reset
    face_tracker_.reset();
    job = track(d, frame_faces);
  }
  pending_ = fitter_.submit([this, job = std::move(job)]() mutable { return fit(std::move(job)); });
  return last_;
}

CaptureSummary FaceCapture::finish() {
  finish_pending_fit();
  end_shot();
  summary_.timings.fit_ms -= summary_.timings.iris_ms;  // the tracker runs the iris searches
  summary_.identity = summary_.shots.empty() ? tracker_.identity() : summary_.shots.front().identity;
  return summary_;
}

}  // namespace facecap
