#pragma once
// The coarse fit of §4.1: the energy E = E_lan + E_prior + E_s (eq. 4.3-4.6)
// minimised by trust-region (Levenberg-Marquardt) steps.
//  - fit_frame: one frame's pose and expression with identity and focal
//    fixed: block coordinate descent (pose, then expression, frame_solver.hpp)
//    followed by a joint step, jaw correspondences re-chosen from the current
//    pose between rounds; temporal terms to the previous frame; with the
//    frame's irises, a pull of the eyeLook weights toward their gaze.
//  - fit_identity: identity and focal jointly over several frames, each
//    frame's pose and expression free (identity_solver.hpp).
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "facecap/detect/landmarks.hpp"
#include "facecap/fit/fit_options.hpp"
#include "facecap/fit/frame_block.hpp"
#include "facecap/fit/gaze.hpp"
#include "facecap/fit/identity_solver.hpp"
#include "facecap/fit/landmark_basis.hpp"
#include "facecap/model/eye_look.hpp"

namespace facecap {

class FrameEnergy;

// A frame's iris centres and the eyeballs they lie on: with them, fit_frame
// pulls the eyeLook weights toward the gaze they show at the current pose
// (eye_look.hpp), by FitWeights::sigma_eye_look.
struct GazeCue {
  const EyeballGeometry* eyes = nullptr;
  IrisCentres irises;
};

struct FrameFitReport {
  double landmark_error = 0;  // NME of the fitted landmarks against the observed ones
  Correspondences correspondences{};
  bool converged = true;
};

class FaceFitter {
 public:
  FaceFitter(const FaceModel& model, const CoarseFitOptions& options, int width, int height);

  const CoarseFitOptions& options() const { return options_; }
  int num_expressions() const { return num_expressions_; }
  int identity_modes() const { return static_cast<int>(basis_.identity.cols()); }
  double focal_guess() const;
  PinholeCamera camera(double focal) const { return {focal, 0.5 * width_, 0.5 * height_}; }
  bool slide_jaw() const { return options_.jaw == JawCorrespondence::kSlide; }
  // The model vertices the landmarks are fitted to (the 68 and the jaw outline's candidates).
  const std::vector<int>& landmark_vertices() const { return basis_.vertices; }

  // A starting pose for a frame with no history: translation from the face's
  // size and position, rotation from the best of a few yaw guesses.
  void initialize_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                        FrameParameters& params) const;

  // Fits pose and expression of one frame (params: in = start, out = fit),
  // tied by the temporal terms to the previous frame's fit.
  FrameFitReport fit_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                           const FrameParameters* previous, FrameParameters& params,
                           const GazeCue* gaze = nullptr) const;
  // Fits a frame again from its own fit (params: in = that fit, out = the
  // new one), tied to the next frame's fit as well as the previous one's (a
  // smoothing pass; coarse_tracker.hpp). From so near a start one joint solve
  // does what fit_frame's rounds do: on `eval track --synthetic 90`, seeds
  // 1-16, every error as with two rounds to the third decimal (jitter 0.136
  // mm, weights 0.0476), at 0.7-0.9 instead of 1.7-1.9 ms a frame (720p).
  FrameFitReport refit_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                             const FrameParameters* previous, const FrameParameters& next, FrameParameters& params,
                             const GazeCue* gaze = nullptr) const;

  // Fits identity and focal jointly with every frame's pose and expression.
  // With `irises` (one per frame), the gaze they show pulls each frame's
  // eyeLook weights as in fit_frame.
  IdentitySolveReport fit_identity(const std::vector<Landmarks>& observed, std::vector<FrameParameters>& frames,
                                   Eigen::VectorXd& identity, double& focal,
                                   const std::vector<IrisCentres>* irises = nullptr) const;

  // The model's 68 landmark points for a fit in camera space (cm); the jaw
  // landmarks are the outline points nearest to the observed ones
  // (jaw_contour.hpp).
  LandmarkPoints landmark_points(const FrameParameters& params, const Eigen::VectorXd& identity, double focal,
                                 const Landmarks& observed, Correspondences* correspondences = nullptr) const;
  // The same points projected.
  Landmarks project(const FrameParameters& params, const Eigen::VectorXd& identity, double focal,
                    const Landmarks& observed, Correspondences* correspondences = nullptr) const;
  Landmarks project(const LandmarkPoints& points, double focal) const;

  double landmark_error(const Landmarks& observed, const FrameParameters& params, const Eigen::VectorXd& identity,
                        double focal) const;

 private:
  // The landmarks' model points at `params`' pose (the jaw's follow the
  // silhouette), set on `energy` and returned.
  Correspondences match_landmarks(FrameEnergy& energy, const Landmarks& observed, const Eigen::VectorXd& identity,
                                  double focal, const FrameParameters& params) const;
  // Pulls the eyeLook weights of `energy` toward the gaze the cue's irises show at `pose`.
  void pull_eye_look(FrameEnergy& energy, const GazeCue& gaze, const HeadPose& pose, double focal, double sigma) const;

  const FaceModel& model_;
  CoarseFitOptions options_;
  int width_, height_;
  int num_expressions_;
  LandmarkBasis basis_;
  EyeLookShapes eye_look_;
};

}  // namespace facecap
