#pragma once
// Coarse tracking of a video (§4.1): identity and focal length are solved
// jointly over the first frames that show a face (several frames, so that head
// motion makes the focal length observable) and then held fixed; every frame's
// pose and expression follow by block coordinate descent with temporal terms
// to the previous frame. A still image is the one-frame case with a stronger
// focal prior. The identity's size is then moved from the joint solve's
// mode to where its posterior mass lies (identity_size.hpp).
//
// Frames go in as they arrive; fits come out in frame order once they are
// final (the first ones after the identity solve, then one per frame, or with
// CoarseFitOptions::smooth_frames, that many at a time).
//
// Smoothing: a fit tied only to the frame before lags behind the face and
// passes the landmarks' noise on. With smooth_frames, each block of frames is
// fitted forward as above, then once more backward, each frame tied to the
// next one's smoothed fit as well as to the previous one's (one backward
// sweep of Gauss-Seidel on the whole sequence's energy, eq. 4.3 summed over
// the frames; each frame one joint solve from its forward fit,
// FaceFitter::refit_frame).
#include <optional>
#include <vector>

#include "facecap/fit/face_fitter.hpp"

namespace facecap {

// Per-frame result of the coarse fit.
struct CoarseFit {
  int index = 0;
  double time = 0.0;
  bool valid = false;  // false: no face, or landmarks the model cannot explain
  HeadPose pose;
  double focal = 0.0;
  Eigen::VectorXf expression;                             // 53 weights in [0, 1]
  double landmark_error = 0.0;                            // NME of the projected fit against the observed landmarks
  Landmarks observed = zero_landmarks();                  // the detector's landmarks
  Landmarks fitted = zero_landmarks();                    // the model's landmarks projected
  LandmarkPoints fitted_points = zero_landmark_points();  // ...and in camera space (cm), unprojected
  Correspondences correspondences{};
  IrisPair irises;    // the iris centres found inside the eye landmarks (iris.hpp), with an IrisSearch
  GazeEstimate gaze;  // from the irises on the fitted head (gaze.hpp)
};

struct IdentityEstimate {
  Eigen::VectorXd identity;  // leading ICT modes
  double focal = 0.0;
  int frames_used = 0;
  double focal_guess = 0.0;
  double solve_ms = 0.0;         // time of the joint identity and focal solve (its iris searches not counted)
  double effective_modes = 0.0;  // identity directions the landmarks determined (identity_solver.hpp)
  double size_factor = 1.0;      // how much larger the size correction made the face (identity_size.hpp)
  // Posterior covariance of `identity` (identity_solver.hpp), for
  // shape_uncertainty.hpp's diagnostics in `eval track`. Not shown to users:
  // the identity solve weighs any number of frames as
  // identity_evidence_frames' (a photo as 30 frames'), so a photo's posterior
  // claims as much as a video's.
  Eigen::MatrixXd covariance;
};

class CoarseTracker {
 public:
  CoarseTracker(const FaceModel& model, const CoarseFitOptions& options, int width, int height);

  // Next frame (landmarks, or nullopt when no face was found). With an iris
  // search, the frame's irises are found at its starting pose's depth, their
  // gaze guides the eyeLook weights (face_fitter.hpp: GazeCue), and the fit
  // reports both. Until the identity is solved (init_frames frames with a
  // face, or init_patience without one) the frames wait and come out together.
  std::vector<CoarseFit> push(int index, double time, const std::optional<Landmarks>& landmarks,
                              IrisSearch iris_search = {});
  // End of input: fits still waiting for the identity solve or smoothing.
  std::vector<CoarseFit> finish();
  // The index of the last frame fitted as lost (no landmarks, or landmarks
  // its fit rejected; the fit may come out later, with smoothing), or -1.
  int last_rejected() const { return last_rejected_; }
  // After finish(), at a shot cut: the frames from here on are another shot
  // (maybe another person, another lens), so their identity and focal length
  // are solved afresh over its first frames, with no temporal link across it.
  void start_shot();

  bool initialized() const { return initialized_; }
  const IdentityEstimate& identity() const { return identity_; }
  const FaceFitter& fitter() const { return fitter_; }

 private:
  struct Pending {
    int index;
    double time;
    std::optional<Landmarks> landmarks;
    IrisSearch iris_search;
    std::optional<IrisPair> irises;  // once searched (for the identity solve)
  };
  // A frame fitted forward, waiting for the smoothing pass.
  struct Forward {
    CoarseFit fit;
    FrameParameters params;
    bool gaze_cued = false;  // fitted with its irises' gaze
  };
  void initialize();
  void reset_identity();  // the mean face at the focal length's guess, not yet solved
  std::vector<CoarseFit> release_pending();
  Forward track(const Pending& frame);
  // The fit's outputs for `params`, as fit_frame reported them.
  void describe(const FrameParameters& params, const FrameFitReport& report, const GazeCue* gaze, CoarseFit& fit) const;
  // Fits ready to go out: `forward` at once, or blocks once smoothed.
  std::vector<CoarseFit> deliver(Forward forward);
  // Smooths the waiting block and hands it out; all of it at the input's
  // end, else all but its last frame (the next block's first needs it).
  std::vector<CoarseFit> smooth_block(bool end);

  const FaceModel& model_;
  FaceFitter fitter_;
  IdentityEstimate identity_;
  EyeballGeometry eyeballs_;  // of the identity, once solved
  bool initialized_ = false;
  std::vector<Pending> pending_;
  int pending_faces_ = 0;
  std::optional<FrameParameters> previous_;
  std::vector<Forward> block_;                    // fitted forward, not yet smoothed
  std::optional<FrameParameters> last_smoothed_;  // the last frame handed out, where it is valid
  int last_rejected_ = -1;
};

}  // namespace facecap
