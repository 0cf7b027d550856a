#include "facecap/fit/coarse_tracker.hpp"

#include <algorithm>
#include <chrono>

#include "facecap/core/parallel.hpp"
#include "facecap/fit/identity_size.hpp"

namespace facecap {

CoarseTracker::CoarseTracker(const FaceModel& model, const CoarseFitOptions& options, int width, int height)
    : model_(model), fitter_(model, options, width, height) {
  reset_identity();
}

void CoarseTracker::reset_identity() {
  identity_ = IdentityEstimate{};
  identity_.identity = Eigen::VectorXd::Zero(fitter_.identity_modes());
  identity_.focal_guess = fitter_.focal_guess();
  identity_.focal = identity_.focal_guess;
  initialized_ = false;
}

void CoarseTracker::start_shot() {
  pending_.clear();
  pending_faces_ = 0;
  previous_.reset();
  block_.clear();
  last_smoothed_.reset();
  reset_identity();
}

std::vector<CoarseFit> CoarseTracker::push(int index, double time, const std::optional<Landmarks>& landmarks,
                                           IrisSearch iris_search) {
  if (initialized_) return deliver(track({index, time, landmarks, std::move(iris_search), std::nullopt}));
  pending_.push_back({index, time, landmarks, std::move(iris_search), std::nullopt});
  if (landmarks) ++pending_faces_;
  // A known identity and focal length need no frames to solve them from.
  const CoarseFitOptions& o = fitter_.options();
  const int needed = o.known_identity && o.focal_known ? 1 : o.init_frames;
  const int faceless = int(pending_.size()) - pending_faces_;
  if (pending_faces_ < needed && faceless < o.init_patience) return {};
  return release_pending();
}

std::vector<CoarseFit> CoarseTracker::finish() {
  std::vector<CoarseFit> out = release_pending();
  for (CoarseFit& fit : smooth_block(true)) out.push_back(std::move(fit));
  return out;
}

std::vector<CoarseFit> CoarseTracker::release_pending() {
  std::vector<CoarseFit> out;
  if (!initialized_ && pending_faces_ > 0) initialize();
  for (const Pending& p : pending_) {
    Forward lost;
    lost.fit.index = p.index;
    lost.fit.time = p.time;
    if (!initialized_) last_rejected_ = p.index;
    for (CoarseFit& fit : deliver(initialized_ ? track(p) : std::move(lost))) out.push_back(std::move(fit));
  }
  pending_.clear();
  pending_faces_ = 0;
  return out;
}

std::vector<CoarseFit> CoarseTracker::deliver(Forward forward) {
  const int block = fitter_.options().smooth_frames;
  if (block <= 0) return {std::move(forward.fit)};
  if (!forward.fit.valid) {
    // The chain breaks here: the frames before it have all the next frames
    // they will have, and this one has nothing to smooth.
    std::vector<CoarseFit> out = smooth_block(true);
    out.push_back(std::move(forward.fit));
    last_smoothed_.reset();
    return out;
  }
  block_.push_back(std::move(forward));
  return int(block_.size()) > block ? smooth_block(false) : std::vector<CoarseFit>{};
}

std::vector<CoarseFit> CoarseTracker::smooth_block(bool end) {
  // The block holds valid fits only: a frame lost ends it (deliver).
  const int n = static_cast<int>(block_.size());
  const int out = end ? n : n - 1;
  // Backward: the next frame's fit is smoothed already, the previous one's
  // not. The block's last frame is left as it is: where the input goes on,
  // it starts the next block; at the input's end, with no next frame, its
  // forward fit is its smoothed one.
  for (int k = n - 2; k >= 0; --k) {
    Forward& f = block_[k];
    const FrameParameters* previous = k > 0 ? &block_[k - 1].params : (last_smoothed_ ? &*last_smoothed_ : nullptr);
    std::optional<GazeCue> gaze;
    if (f.gaze_cued) gaze = GazeCue{&eyeballs_, iris_centres(f.fit.irises)};
    FrameParameters params = f.params;  // starts from the forward fit
    const FrameFitReport report = fitter_.refit_frame(f.fit.observed, identity_.identity, identity_.focal, previous,
                                                      block_[k + 1].params, params, gaze ? &*gaze : nullptr);
    if (report.landmark_error > fitter_.options().lost_landmark_error) continue;  // keep the forward fit
    describe(params, report, gaze ? &*gaze : nullptr, f.fit);
    f.params = std::move(params);
  }
  std::vector<CoarseFit> fits;
  for (int k = 0; k < out; ++k) fits.push_back(std::move(block_[k].fit));
  if (out > 0) last_smoothed_ = block_[out - 1].params;
  block_.erase(block_.begin(), block_.begin() + out);
  return fits;
}

void CoarseTracker::initialize() {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Landmarks> observed;
  std::vector<Pending*> faces;
  for (Pending& p : pending_) {
    if (!p.landmarks) continue;
    observed.push_back(*p.landmarks);
    faces.push_back(&p);
  }

  const int nf = fitter_.num_expressions();
  const std::optional<Eigen::VectorXd>& known = fitter_.options().known_identity;
  Eigen::VectorXd identity = known ? *known : Eigen::VectorXd::Zero(fitter_.identity_modes());
  double focal = fitter_.focal_guess();
  std::vector<FrameParameters> frames(observed.size(), FrameParameters(nf));
  // Each frame on its own with the mean face first, then everything jointly.
  // The irises are found once each frame has a pose, and their gaze guides
  // the eyeLook weights in the joint solve too.
  const EyeballGeometry mean_eyes = eyeball_geometry(model_, identity);
  std::vector<IrisCentres> irises(observed.size());
  bool any_iris = false;
  double search_ms = 0.0;  // the iris searches are not part of the solve's time
  // The frames' fits are independent (the mean face, no temporal link).
  parallel_for(
      static_cast<int>(observed.size()),
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          fitter_.initialize_frame(observed[i], identity, focal, frames[i]);
          fitter_.fit_frame(observed[i], identity, focal, nullptr, frames[i]);
        }
      },
      1);
  for (size_t i = 0; i < observed.size(); ++i) {
    if (faces[i]->iris_search) {
      const auto search_start = std::chrono::steady_clock::now();
      faces[i]->irises = faces[i]->iris_search(expected_irises(mean_eyes, frames[i].pose(), fitter_.camera(focal)));
      search_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - search_start).count();
      irises[i] = iris_centres(*faces[i]->irises);
      any_iris = true;
    }
  }
  const std::vector<IrisCentres>* cues = any_iris ? &irises : nullptr;
  IdentitySolveReport solve = fitter_.fit_identity(observed, frames, identity, focal, cues);

  // Frames whose landmarks the joint model cannot explain (a detector
  // failure) must not shape the identity: drop them and solve again.
  std::vector<Landmarks> kept;
  std::vector<FrameParameters> kept_frames;
  std::vector<IrisCentres> kept_irises;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (fitter_.landmark_error(observed[i], frames[i], identity, focal) <= fitter_.options().lost_landmark_error) {
      kept.push_back(observed[i]);
      kept_frames.push_back(frames[i]);
      kept_irises.push_back(irises[i]);
    }
  }
  if (!kept.empty() && kept.size() < observed.size()) {
    solve = fitter_.fit_identity(kept, kept_frames, identity, focal, any_iris ? &kept_irises : nullptr);
  }
  if (fitter_.options().unbiased_size && !known) {  // a known identity has its size
    const IdentitySizeCorrection size(model_, fitter_.identity_modes(), fitter_.landmark_vertices());
    identity_.size_factor = size.factor(identity, solve.effective_modes);
    identity = size.scale(identity, identity_.size_factor);
  }
  // The solve's posterior, scaled with the face (c (a + m) - m).
  identity_.covariance = identity_.size_factor * identity_.size_factor * solve.identity_covariance;
  identity_.identity = identity;
  identity_.focal = focal;
  eyeballs_ = eyeball_geometry(model_, identity);
  identity_.effective_modes = solve.effective_modes;
  if (known) {  // not solved here: no posterior of this input's to report
    identity_.effective_modes = 0;
    identity_.covariance.resize(0, 0);
  }
  identity_.frames_used = static_cast<int>(kept.empty() ? observed.size() : kept.size());
  initialized_ = true;
  identity_.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() - search_ms;
}

CoarseTracker::Forward CoarseTracker::track(const Pending& frame) {
  Forward out;
  CoarseFit& fit = out.fit;
  fit.index = frame.index;
  fit.time = frame.time;
  fit.focal = identity_.focal;
  if (!frame.landmarks) {
    previous_.reset();  // no temporal link across a gap
    last_rejected_ = fit.index;
    return out;
  }
  FrameParameters params(fitter_.num_expressions());
  if (previous_) {
    params = *previous_;
  } else {
    fitter_.initialize_frame(*frame.landmarks, identity_.identity, identity_.focal, params);
  }
  const FrameParameters* previous = previous_ ? &*previous_ : nullptr;
  const PinholeCamera camera = fitter_.camera(identity_.focal);
  std::optional<GazeCue> gaze;
  if (frame.irises) {
    fit.irises = *frame.irises;  // found during the identity solve
  } else if (frame.iris_search) {
    // The starting pose's depth (the previous frame's) sizes the irises well enough.
    fit.irises = frame.iris_search(expected_irises(eyeballs_, params.pose(), camera));
  }
  if (frame.iris_search) gaze = GazeCue{&eyeballs_, iris_centres(fit.irises)};
  const GazeCue* cue = gaze ? &*gaze : nullptr;
  FrameFitReport report =
      fitter_.fit_frame(*frame.landmarks, identity_.identity, identity_.focal, previous, params, cue);
  if (report.landmark_error > fitter_.options().lost_landmark_error && previous != nullptr) {
    // Maybe the warm start was the problem (a fast turn): start afresh once.
    FrameParameters fresh(fitter_.num_expressions());
    fitter_.initialize_frame(*frame.landmarks, identity_.identity, identity_.focal, fresh);
    const FrameFitReport second =
        fitter_.fit_frame(*frame.landmarks, identity_.identity, identity_.focal, nullptr, fresh, cue);
    if (second.landmark_error < report.landmark_error) {
      report = second;
      params = fresh;
    }
  }
  fit.observed = *frame.landmarks;
  describe(params, report, cue, fit);
  if (fit.valid) {
    previous_ = params;
  } else {
    previous_.reset();
    last_rejected_ = fit.index;
  }
  out.params = std::move(params);
  out.gaze_cued = cue != nullptr;
  return out;
}

void CoarseTracker::describe(const FrameParameters& params, const FrameFitReport& report, const GazeCue* gaze,
                             CoarseFit& fit) const {
  fit.landmark_error = report.landmark_error;
  fit.correspondences = report.correspondences;
  fit.pose = params.pose();
  fit.expression = params.expression().cast<float>();
  fit.fitted_points = fitter_.landmark_points(params, identity_.identity, identity_.focal, fit.observed);
  fit.fitted = fitter_.project(fit.fitted_points, identity_.focal);
  fit.valid = report.landmark_error <= fitter_.options().lost_landmark_error;
  if (!fit.valid) fit.irises = {};
  fit.gaze = {};
  if (gaze != nullptr && fit.valid)
    fit.gaze = estimate_gaze(eyeballs_, fit.pose, fitter_.camera(identity_.focal), gaze->irises);
}

}  // namespace facecap
