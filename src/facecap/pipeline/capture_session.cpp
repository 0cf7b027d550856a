#include "facecap/pipeline/capture_session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "facecap/core/bounded_queue.hpp"

#include "facecap/core/interrupt.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/core/stopwatch.hpp"

namespace facecap {

std::string unreadable_frames_note(const CaptureSummary& summary, const std::string& what) {
  if (summary.unreadable == 0) return "";
  return std::to_string(summary.unreadable) + " frame(s) of " + what +
         " could not be read and are lost (the first: " + summary.first_error + ")";
}

CaptureSummary run_capture(const FaceModel& model, FrameSource& source, CaptureOptions options, const FrameSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  CaptureSummary summary;
  summary.input = source.info();
  if (summary.input.kind == InputKind::kImage) {
    options.fit.still = true;
    options.fit.init_frames = 1;
  }
  const LandmarkDetector landmark_detector;
  FaceTracker face_tracker(landmark_detector, options.tracker);
  CoarseTracker tracker(model, options.fit, summary.input.width, summary.input.height);
  summary.timings.setup_ms = ms_since(start);

  struct Waiting {
    TrackStatus status;
    int faces_seen;
    cv::Mat image;
    std::string error;
    int shot;
  };
  std::map<int, Waiting> waiting;  // frames whose fit is not final yet
  auto deliver = [&](const std::vector<CoarseFit>& fits) {
    for (const CoarseFit& fit : fits) {
      auto it = waiting.find(fit.index);
      CapturedFrame out;
      out.index = fit.index;
      out.time = fit.time;
      out.fit = fit;
      out.status = fit.valid ? it->second.status : TrackStatus::kLost;
      out.faces_seen = it->second.faces_seen;
      out.image = it->second.image;
      out.error = it->second.error;
      out.identity = tracker.identity();
      out.shot = it->second.shot;
      waiting.erase(it);
      summary.lost += out.status == TrackStatus::kLost;
      summary.redetected += out.status == TrackStatus::kRedetected;
      summary.most_faces = std::max(summary.most_faces, out.faces_seen);
      if (!out.error.empty() && summary.unreadable++ == 0) summary.first_error = out.error;
      ++summary.frames;
      sink(out);
    }
  };

  const int remaining = summary.input.frames > 0 ? summary.input.frames - summary.input.first_frame : -1;
  const int total =
      options.max_frames > 0 && (remaining <= 0 || options.max_frames < remaining) ? options.max_frames : remaining;
  Progress progress("capture", total, options.quiet);
  StageTimings& t = summary.timings;

  // The tracker's output, timed: its identity solves (one a shot) apart from
  // the per-frame fits.
  auto timed = [&](auto&& call) {
    const bool was_initialized = tracker.initialized();
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<CoarseFit> fits = call();
    t.fit_ms += ms_since(t0);
    if (!was_initialized && tracker.initialized()) {
      t.identity_ms += tracker.identity().solve_ms;
      t.fit_ms -= tracker.identity().solve_ms;
    }
    return fits;
  };
  // A shot ends: its frames still waiting are fitted with what it showed,
  // and its identity is kept.
  int shot = 0, shot_start = summary.input.first_frame;
  auto end_shot = [&] {
    deliver(timed([&] { return tracker.finish(); }));
    if (tracker.initialized()) summary.shots.push_back({shot, shot_start, tracker.identity()});
  };
  ShotCutDetector cuts(options.shot_cut);
  const bool find_cuts = options.shot_cuts && summary.input.kind != InputKind::kImage;

  // Decoding (and the grey conversion the landmarks need) runs on its own
  // thread, a few frames ahead of the landmark and fit stages.
  struct Decoded {
    Frame frame;
    cv::Mat grey;
    double decode_ms = 0;
  };
  BoundedQueue<Decoded> decoded(4);
  std::exception_ptr decode_error;
  std::jthread decoder([&] {
    try {
      for (int n = 0; options.max_frames <= 0 || n < options.max_frames; ++n) {
        Decoded d;
        const auto t0 = std::chrono::steady_clock::now();
        if (!source.read(d.frame)) break;
        if (!d.frame.image.empty()) cv::cvtColor(d.frame.image, d.grey, cv::COLOR_BGR2GRAY);
        d.decode_ms = ms_since(t0);
        if (!decoded.push(std::move(d))) break;
      }
    } catch (...) {
      decode_error = std::current_exception();
    }
    decoded.close();
  });
  struct CloseOnExit {
    BoundedQueue<Decoded>& q;
    ~CloseOnExit() { q.close(); }  // unblocks the decoder if a stage throws
  } close_on_exit{decoded};

  // A camera has no end of its own: Ctrl-C ends it, and what was captured is
  // kept. Anything else is a job that was stopped: nothing is written.
  const bool live = summary.input.kind == InputKind::kCamera;
  struct LiveInput {
    explicit LiveInput(bool live) { set_interrupt_ends_input(live); }
    ~LiveInput() { set_interrupt_ends_input(false); }
  } live_input{live};
  while (std::optional<Decoded> d = decoded.pop()) {
    if (live && interrupted()) {
      clear_interrupt();
      summary.stopped_by_user = true;
      decoded.close();  // the decoder stops at its next frame
      break;
    }
    throw_if_interrupted();
    const Frame& frame = d->frame;
    t.decode_ms += d->decode_ms;

    if (find_cuts && cuts.next(d->grey)) {
      end_shot();
      tracker.start_shot();
      face_tracker.start_shot();  // the last shot's box says nothing of this one
      ++shot;
      shot_start = frame.index;
      ++summary.cuts;
    }
    TrackedFace face;
    if (!d->grey.empty()) face = face_tracker.next(d->grey);
    t.detect_ms += face.detector_ms;
    t.landmarks_ms += face.landmarks_ms;

    std::optional<Landmarks> landmarks;
    if (face.status != TrackStatus::kLost) landmarks = face.landmarks;
    // A frame the input could not give is kept as a black one of the input's
    // size, so that output videos keep every frame in its place.
    cv::Mat kept;
    if (options.keep_images) {
      kept = frame.image.empty() ? cv::Mat(summary.input.height, summary.input.width, CV_8UC3, cv::Scalar::all(0))
                                 : frame.image;
    }
    waiting[frame.index] = {face.status, face.faces_seen, kept, frame.error, shot};
    IrisSearch iris_search;
    if (landmarks && options.gaze) {
      // Timed where the tracker calls it (maybe later, after the identity solve).
      iris_search = [search = facecap::iris_search(d->grey, *landmarks),
                     &t](const std::array<IrisExpectation, 2>& expected) {
        const auto t0 = std::chrono::steady_clock::now();
        IrisPair irises = search(expected);
        t.iris_ms += ms_since(t0);
        return irises;
      };
    }

    const std::vector<CoarseFit> fits =
        timed([&] { return tracker.push(frame.index, frame.time, landmarks, std::move(iris_search)); });
    // A fit that rejects the landmarks means the box tracker followed
    // something that is not the face: detect afresh on the next frame.
    for (const CoarseFit& fit : fits) {
      if (!fit.valid && fit.index == frame.index) face_tracker.reset();
    }
    deliver(fits);
    ++t.frames;
    progress.update(t.frames);
  }
  decoder.join();
  if (decode_error) std::rethrow_exception(decode_error);
  end_shot();
  t.fit_ms -= t.iris_ms;  // the tracker runs the iris searches
  progress.finish();
  if (summary.stopped_by_user && !options.quiet)
    std::fprintf(stderr, "facecap: the camera was stopped (Ctrl-C) after %d frames; they are written\n", t.frames);
  summary.identity = summary.shots.empty() ? tracker.identity() : summary.shots.front().identity;
  t.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace facecap
