#include "facecap/fit/face_fitter.hpp"

#include <cmath>
#include <optional>

#include "facecap/core/parallel.hpp"
#include "facecap/fit/frame_energy.hpp"
#include "facecap/fit/frame_solver.hpp"
#include "facecap/fit/identity_solver.hpp"

namespace facecap {

FaceFitter::FaceFitter(const FaceModel& model, const CoarseFitOptions& options, int width, int height)
    : model_(model),
      options_(options),
      width_(width),
      height_(height),
      num_expressions_(model.num_expressions()),
      basis_(gather_landmark_basis(model, options.identity_modes)),
      eye_look_(model) {
  options_.check();
}

double FaceFitter::focal_guess() const {
  return options_.focal_guess > 0 ? options_.focal_guess : 1.0 * std::max(width_, height_);
}

LandmarkPoints FaceFitter::landmark_points(const FrameParameters& params, const Eigen::VectorXd& identity, double focal,
                                           const Landmarks& observed, Correspondences* correspondences) const {
  const HeadPose pose = params.pose();
  const Mat3d rf = pose.model_to_camera_rotation();
  const Eigen::VectorXd w = params.expression();
  const Correspondences c =
      pose_correspondences(model_, basis_, identity, w, pose, camera(focal), observed, slide_jaw());
  if (correspondences != nullptr) *correspondences = c;
  LandmarkPoints out;
  for (int i = 0; i < kNumLandmarks; ++i) {
    const Vec3d x = (1.0 - c[i].t) * basis_.position(basis_.slot(c[i].a), identity, w) +
                    c[i].t * basis_.position(basis_.slot(c[i].b), identity, w);
    out[i] = rf * x + pose.translation;
  }
  return out;
}

Landmarks FaceFitter::project(const LandmarkPoints& points, double focal) const {
  const PinholeCamera cam = camera(focal);
  Landmarks out;
  for (int i = 0; i < kNumLandmarks; ++i) out[i] = cam.project(points[i]).cast<float>();
  return out;
}

Landmarks FaceFitter::project(const FrameParameters& params, const Eigen::VectorXd& identity, double focal,
                              const Landmarks& observed, Correspondences* correspondences) const {
  return project(landmark_points(params, identity, focal, observed, correspondences), focal);
}

double FaceFitter::landmark_error(const Landmarks& observed, const FrameParameters& params,
                                  const Eigen::VectorXd& identity, double focal) const {
  return landmark_nme(project(params, identity, focal, observed), observed);
}

void FaceFitter::initialize_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                                  FrameParameters& params) const {
  // Depth from the eye-corner distance (8.9 cm on the mean face; the eyes sit
  // about 9 cm in front of the model origin), position from the landmark centre.
  const double eye_px = std::max(1.0f, outer_eye_distance(observed));
  const double depth = focal * 8.9 / eye_px + 9.0;
  Vec2d centre = Vec2d::Zero();
  for (const Vec2f& p : observed) centre += p.cast<double>() / 68.0;
  const Eigen::Vector2d pp(0.5 * width_, 0.5 * height_);
  const Vec2d eyes = (observed[45] - observed[36]).cast<double>();
  const double roll = std::atan2(eyes.y(), eyes.x()) * 180.0 / 3.14159265358979323846;

  FrameEnergy energy(basis_, options_.weights, observed, pp, identity, focal, nullptr);
  double best_cost = std::numeric_limits<double>::infinity();
  FrameParameters best(num_expressions_);
  for (double yaw : {0.0, -30.0, 30.0}) {
    FrameParameters trial(num_expressions_);
    HeadPose pose;
    pose.rotation = axis_angle_from_rotation(rotation_from_yaw_pitch_roll_deg(yaw, 0.0, roll));
    pose.translation = Vec3d((centre.x() - pp.x()) * depth / focal, (centre.y() - pp.y()) * depth / focal + 1.0, depth);
    trial.set_pose(pose);
    for (int round = 0; round < 2; ++round) {
      match_landmarks(energy, observed, identity, focal, trial);
      solve_pose(energy, trial, 15);
    }
    const double c = energy.cost(trial);
    if (c < best_cost && trial.values[frame_block::kTranslation + 2] > 0) {
      best_cost = c;
      best = trial;
    }
  }
  params = best;
}

Correspondences FaceFitter::match_landmarks(FrameEnergy& energy, const Landmarks& observed,
                                            const Eigen::VectorXd& identity, double focal,
                                            const FrameParameters& params) const {
  Correspondences c = pose_correspondences(model_, basis_, identity, params.expression(), params.pose(), camera(focal),
                                           observed, slide_jaw());
  energy.set_correspondences(c);
  return c;
}

FrameFitReport FaceFitter::fit_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                                     const FrameParameters* previous, FrameParameters& params,
                                     const GazeCue* gaze) const {
  const Eigen::Vector2d pp(0.5 * width_, 0.5 * height_);
  FrameEnergy energy(basis_, options_.weights, observed, pp, identity, focal, previous);
  FrameFitReport report;
  for (int round = 0; round < options_.bcd_iterations; ++round) {
    // Jaw correspondences follow the current pose (landmark marching).
    report.correspondences = match_landmarks(energy, observed, identity, focal, params);
    solve_pose(energy, params, options_.max_solver_iterations);
    // The gaze depends on the pose (where the eyeballs sit under the irises), not on the weights.
    if (gaze != nullptr) pull_eye_look(energy, *gaze, params.pose(), focal, options_.weights.sigma_eye_look);
    solve_expression(energy, params, 5);
    solve_joint(energy, params, options_.max_solver_iterations);
  }
  report.landmark_error = landmark_error(observed, params, identity, focal);
  return report;
}

FrameFitReport FaceFitter::refit_frame(const Landmarks& observed, const Eigen::VectorXd& identity, double focal,
                                       const FrameParameters* previous, const FrameParameters& next,
                                       FrameParameters& params, const GazeCue* gaze) const {
  const Eigen::Vector2d pp(0.5 * width_, 0.5 * height_);
  FrameEnergy energy(basis_, options_.weights, observed, pp, identity, focal, previous, &next);
  FrameFitReport report;
  report.correspondences = match_landmarks(energy, observed, identity, focal, params);
  if (gaze != nullptr) pull_eye_look(energy, *gaze, params.pose(), focal, options_.weights.sigma_eye_look);
  solve_joint(energy, params, options_.max_solver_iterations);
  report.landmark_error = landmark_error(observed, params, identity, focal);
  return report;
}

void FaceFitter::pull_eye_look(FrameEnergy& energy, const GazeCue& gaze, const HeadPose& pose, double focal,
                               double sigma) const {
  const GazeEstimate g = estimate_gaze(*gaze.eyes, pose, camera(focal), gaze.irises);
  if (g.valid()) energy.set_expression_targets(eye_look_.weights(g.angles_deg()), sigma);
}

IdentitySolveReport FaceFitter::fit_identity(const std::vector<Landmarks>& observed,
                                             std::vector<FrameParameters>& frames, Eigen::VectorXd& identity,
                                             double& focal, const std::vector<IrisCentres>* irises) const {
  const Eigen::Vector2d pp(0.5 * width_, 0.5 * height_);
  FitWeights weights = options_.weights;
  weights.sigma_landmark *= weights.identity_sigma_factor;
  // The landmarks weigh as N video frames' (identity_evidence_frames) however
  // many frames there are: each of K frames (a photo, a burst of source
  // photos, a long start of a video) as N / K frames'. A frame's whole energy
  // is scaled, its expression prior included: a frame that stands for several
  // of one expression carries the prior as many times, or the identity solve
  // explains the face's shape by expression. For a photo: self-swap (`eval
  // swap --self`) median / mean 5.0 / 7.6 -> 4.7 / 6.6 (address_720p_a),
  // 7.3 / 11.1 -> 6.7 / 10.0 (_b); the portraits' landmark NME
  // 0.0149 / 0.0126 -> 0.0142 / 0.0124.
  const double frame_weight = weights.identity_evidence_frames / double(std::max<size_t>(1, observed.size()));
  weights.sigma_landmark /= std::sqrt(frame_weight);
  weights.sigma_expression /= std::sqrt(frame_weight);
  if (observed.size() == 1) weights.sigma_expression *= weights.photo_expression_sigma_factor;
  std::vector<std::unique_ptr<FrameEnergy>> energies;
  for (const Landmarks& lm : observed) {
    energies.push_back(std::make_unique<FrameEnergy>(basis_, weights, lm, pp, identity, focal, nullptr));
  }
  IdentitySolverOptions o;
  o.focal_free = !options_.focal_known;
  o.identity_free = !options_.known_identity;
  o.focal_guess = focal_guess();
  o.sigma_log_focal = options_.still ? options_.weights.sigma_log_focal_still : options_.weights.sigma_log_focal;
  o.max_iterations = 40;
  o.refresh = [&](const std::vector<FrameParameters>& f, const Eigen::VectorXd& id, double current_focal) {
    // The gaze's pull, weighed like the frame's other terms, on the current identity's eyeballs.
    std::optional<EyeballGeometry> eyes;
    if (irises != nullptr) eyes = eyeball_geometry(model_, id);
    parallel_for(
        static_cast<int>(f.size()),
        [&](int b, int e) {
          for (int i = b; i < e; ++i) {
            match_landmarks(*energies[i], observed[i], id, current_focal, f[i]);
            if (eyes) {
              pull_eye_look(*energies[i], {&*eyes, (*irises)[i]}, f[i].pose(), current_focal,
                            options_.weights.sigma_eye_look / std::sqrt(frame_weight));
            }
          }
        },
        1);
  };
  return solve_identity_joint(energies, frames, identity, focal, o);
}

}  // namespace facecap
