#pragma once
// Weights and options of the coarse fit (paper §4.1, eq. 4.3-4.6).
//
// The paper's weights (w1..w4 = 1e-5, 100, 10, 1) were set for FaceWarehouse
// units and 73 landmarks in pixels. We state every term as a residual divided
// by a standard deviation, which makes each weight a physical statement:
//  - landmarks (eq. 4.4): residual in pixels divided by sigma_landmark x
//    (inter-ocular distance / 100 px), so the fit behaves the same at any
//    resolution; 2 px per 100 px of inter-ocular distance is dlib's typical
//    error (NME about 0.02-0.03);
//  - identity prior (eq. 4.5): a ~ N(0, 1) per ICT mode, as the model defines;
//  - expression prior (eq. 4.5): w / sigma_expression, a weak pull toward the
//    neutral face for weights the landmarks cannot see (eye gaze, cheek puff);
//  - temporal terms (eq. 4.6): frame-to-frame change divided by its typical
//    size at 30 fps (0.1 per weight, 3 degrees, 1.5 cm: a head turns at up to
//    90 degrees a second; 1 degree measured 0.9 degrees of rotation error on
//    turning synthetic heads against 0.5 with 3). Relative to the landmark
//    term these play the role of the paper's 100, 10 and 1.
// Each value can be overridden; Check() rejects impossible ones by name.
#include <Eigen/Core>
#include <optional>
#include <string>

namespace facecap {

struct FitWeights {
  double sigma_landmark = 2.0;    // px per 100 px of inter-ocular distance
  double jaw_sigma_factor = 1.5;  // jaw landmarks (0-16) are less certain: sigma x this
  // The identity solve sees the same landmark offsets in every frame: where a
  // detector's convention differs from the model's landmark vertices (dlib's
  // brows, lips and jaw sit a few per cent of the inter-ocular distance away
  // from ICT's), those errors do not average out over frames and would bend
  // the identity (identity norms of 16 instead of about 7 were measured on
  // real footage). The identity solve therefore uses sigma x this factor.
  double identity_sigma_factor = 3.0;
  // The landmarks weigh in the identity solve as much as this many video
  // frames', however many frames it has: a photo's as these many frames', each
  // of 90 frames' as a third of one. The systematic part of a detector's error
  // is the same in every frame, so more frames show more head poses but no
  // more evidence about the shape.
  //  - Fewer frames (a photo): with one frame's weight the prior pulled a
  //    photo's identity to a third of the video's size (photo vs video
  //    identity of the same speaker, address_720p_a frame 0: distance 7.1
  //    with one frame's weight, 3.9 with 30), and a swap's face toward the
  //    mean face (self-swap median 8.0 -> 5.7 grey levels with 30; the still
  //    fit's landmark NME on the two portraits 0.023 / 0.019 -> 0.015 / 0.013).
  //  - More frames: weighed in full, 90 frames of dlib's landmarks bent the
  //    identity further (synthetic renders with brows centred on their
  //    landmarks, seeds 1-4: vertex error
  //    4.8 / 7.5 / 10.9 / 4.3 mm with 30 frames, 7.0 / 10.6 / 12.5 / 5.5 with 90;
  //    identity norm on address_720p_a 8.3 -> 11.3); 90 frames weighed as 30
  //    frames' give 4.7 / 8.0 / 9.6 / 4.2 mm, and the identities of
  //    address_720p_a and _b (the same speaker) 2.1 apart (3.4 from 30 frames,
  //    3.35 from 90 weighed in full).
  double identity_evidence_frames = 30.0;
  double sigma_expression = 0.6;  // prior on each weight (mean 0)
  // An identity solved from one photo: its expression prior's sigma is this
  // many times what the frame weight above gives it. One photo cannot tell
  // the face's shape from its expression, and with the prior at a video
  // frame's strength the shape took in part of a smile (Obama's portrait:
  // mouthSmile 0.41, and every swap from it grinned). Each frame of
  // synthetic performances fitted alone (`eval track --synthetic 90
  // --photos 3`, seeds 1-6, 180 photos), neutral-face error with the size
  // removed: factor 1 / 1.25 / 1.5 / 1.75 / 2 / 3 gave 1.580 / 1.546 /
  // 1.534 / 1.533 / 1.540 / 1.581 mm; at 1.5 the most expressive half
  // 1.674 -> 1.584 mm, the calmest 1.486 -> 1.484, every seed better or
  // the same. On real photos, the identity's distance to the same person's
  // video identity: Obama's portrait to address_720p_a / _b 8.16 / 7.64 ->
  // 6.94 / 6.37 (smile 0.41 -> 0.51), the clips' frame 0 to their own clip
  // 3.11 -> 3.04, 2.08 -> 1.98. Self-swap means (`eval swap --self`, a
  // clip's frame 0 as the photo): address_720p_a 4.54 -> 4.24, _b 7.49 ->
  // 7.58, emotions_pexels (a crying first frame) 11.06 -> 11.45.
  double photo_expression_sigma_factor = 1.5;
  // Where the irises show a gaze, the eight eyeLook weights are pulled toward
  // its weights (eye_look.hpp) with this sigma (0.35: 10.5 degrees, about
  // the gaze's error with dlib's landmarks). `eval track --synthetic 90`,
  // mean eyeLook weight error on seeds 1-3 without the pull / with sigma
  // 0.1, 0.2, 0.35: true landmarks 0.065 / 0.083 / 0.072 / 0.060, 0.045 /
  // 0.039 / 0.037 / 0.038, 0.049 / 0.068 / 0.056 / 0.046; dlib 0.100 /
  // 0.082 / 0.077 / 0.073, 0.100 / 0.068 / 0.070 / 0.079, 0.126 / 0.113 /
  // 0.106 / 0.105. Tighter, the gaze's own error outweighs true lids.
  double sigma_eye_look = 0.35;
  double expression_l1 = 0.0;  // optional sparsity prior: lambda * sum(w) (w >= 0), in cost units
  double sigma_temporal_expression = 0.1;
  double sigma_temporal_rotation_deg = 3.0;
  double sigma_temporal_translation_cm = 1.5;
  double sigma_log_focal = 0.5;         // video: weak prior on log(focal / guess)
  double sigma_log_focal_still = 0.15;  // single image: focal is barely observable
  double huber_scale = 3.0;             // robust loss on landmarks, in sigmas

  void check() const;
};

// How jaw landmarks (iBUG 0-16) find their model point (jaw_contour.hpp).
enum class JawCorrespondence {
  kSlide,  // nearest point of the projected outline: for detectors whose spacing
           // along the jaw differs from the model's (dlib's sits up to 1.5 cm away)
  kMarch,  // the marched silhouette vertex of each jawline candidate: for
           // landmarks that follow the model's own definition (synthetic truth)
};

struct CoarseFitOptions {
  // A still image: its one frame solves the identity and the focal length.
  void set_single_image() {
    still = true;
    init_frames = 1;
  }

  FitWeights weights;
  int identity_modes = 50;  // leading ICT identity modes fitted (DESIGN.md)
  int init_frames = 30;     // frames for the joint identity + focal solve
  // Frames without a face the solve waits through for its init_frames: past
  // this many it solves from the faces it has (or, with none, lets the frames
  // go as lost), so that a face seen briefly does not hold every later frame,
  // and an edit every later image, until the input ends.
  int init_patience = 150;
  // Frames fitted forward, then smoothed backward, before they come out
  // (coarse_tracker.hpp); 0: each frame comes out as soon as it is fitted,
  // tied to the frame before only, as a camera's should. Synthetic sweeps
  // (`eval track --synthetic 90 --no-gaze`, true landmarks, seeds 1-8): one
  // backward sweep over the whole sweep took the still head's jitter from
  // 0.183 to 0.139 mm and lowered every other error a little (weights
  // 0.0543 -> 0.0537, rotation 0.640 -> 0.624 deg, rigid vertex 1.344 ->
  // 1.336 mm); sweeping to convergence did no better. Blocks of 1 / 4 / 8 /
  // 16 frames: jitter 0.153 / 0.143 / 0.141 / 0.139 mm, the other errors alike
  // (README, "Smoothing").
  int smooth_frames = 8;
  int bcd_iterations = 2;            // per frame: pose, expression, joint, this many rounds
  int max_solver_iterations = 20;    // Levenberg-Marquardt iterations per block solve
  double focal_guess = 0.0;          // pixels; 0 = 1.0 x the larger image side
  bool focal_known = false;          // hold focal_guess fixed (a calibrated camera)
  double lost_landmark_error = 0.1;  // NME of the fit against its landmarks above which a frame counts as lost
  bool still = false;                // a single image: one frame, stronger focal prior (set_single_image)
  JawCorrespondence jaw = JawCorrespondence::kSlide;
  // Move the solved identity's size from the joint posterior's mode to where
  // its mass lies (identity_size.hpp). Synthetic sweeps (`eval track
  // --synthetic 90`, seeds 1-12): size 0.957-0.994 of the truth -> 0.980-1.018,
  // rigid vertex error 2.17 -> 1.30 mm on average.
  bool unbiased_size = true;
  // The face's identity, known from an earlier capture of the same person
  // (`--identity identity.json`): held as given (identity_modes values), so
  // that takes of one actor share one face. The focal length is still solved
  // over the first frames, unless focal_known, when the first frame starts the
  // output.
  std::optional<Eigen::VectorXd> known_identity;

  void check() const;
};

}  // namespace facecap
