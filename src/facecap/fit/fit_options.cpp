#include "facecap/fit/fit_options.hpp"

#include <cmath>
#include <string>

#include "facecap/core/error.hpp"

namespace facecap {

namespace {
void positive(double v, const char* name) {
  if (!(v > 0)) throw Error(std::string("fit option ") + name + " must be positive");
}
}  // namespace

void FitWeights::check() const {
  positive(sigma_landmark, "sigma_landmark");
  positive(jaw_sigma_factor, "jaw_sigma_factor");
  positive(identity_sigma_factor, "identity_sigma_factor");
  positive(identity_evidence_frames, "identity_evidence_frames");
  positive(sigma_expression, "sigma_expression");
  positive(photo_expression_sigma_factor, "photo_expression_sigma_factor");
  positive(sigma_eye_look, "sigma_eye_look");
  positive(sigma_temporal_expression, "sigma_temporal_expression");
  positive(sigma_temporal_rotation_deg, "sigma_temporal_rotation_deg");
  positive(sigma_temporal_translation_cm, "sigma_temporal_translation_cm");
  positive(sigma_log_focal, "sigma_log_focal");
  positive(sigma_log_focal_still, "sigma_log_focal_still");
  positive(huber_scale, "huber_scale");
}

void CoarseFitOptions::check() const {
  weights.check();
  if (identity_modes < 1 || identity_modes > 100) throw Error("--identity-modes must be between 1 and 100");
  if (init_frames < 1) throw Error("--init-frames must be at least 1");
  if (init_patience < 1) throw Error("fit option init_patience must be at least 1");
  if (smooth_frames < 0) throw Error("--smooth-frames must be 0 (off) or more");
  if (bcd_iterations < 1) throw Error("fit option bcd_iterations must be at least 1");
  if (max_solver_iterations < 1) throw Error("fit option max_solver_iterations must be at least 1");
  if (!(focal_guess >= 0 && std::isfinite(focal_guess))) throw Error("--focal must be positive");
  if (focal_known && focal_guess <= 0) throw Error("a known focal length needs --focal");
  if (!(lost_landmark_error > 0)) throw Error("fit option lost_landmark_error must be positive");
  if (known_identity && (known_identity->size() != identity_modes || !known_identity->allFinite()))
    throw Error("a known identity needs " + std::to_string(identity_modes) + " finite identity weights, not " +
                std::to_string(known_identity->size()));
}

}  // namespace facecap
