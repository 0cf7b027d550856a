#pragma once
// `facecap eval track --synthetic N --photos`: how well one photo fixes a
// face's identity, against ground truth. Frames of a synthetic performance
// (head turns, speech and occasional expressions: smiles, raised brows,
// frowns, puckers) are each fitted alone, as `facecap track PHOTO` and a
// swap's source are, from their true landmarks plus Gaussian noise. What a
// single photo cannot separate, the face's shape and its expression, shows
// in the identity's error: a smile the fit leaves in the identity widens
// the mouth of every face made from it.
#include "facecap/pipeline/track_eval.hpp"

namespace facecap {

struct PhotoIdentityEvalResult {
  int photos = 0;
  // The fitted neutral face region against the true one, mean distance over
  // vertices in mm after a similarity alignment (a photo does not fix the
  // size); mean over the photos, and over the half of them with the most and
  // the least expression (the true weights' norm, gaze and blinks aside).
  double shape_error_mm = 0;
  double shape_error_expressive_mm = 0;
  double shape_error_calm_mm = 0;
  // Mean |w - w_true| over the photos and the 53 weights, and over the
  // expressive half's weights that its expressions move.
  double weights_mae = 0;
  double expression_mae_expressive = 0;
};

// Fits every `stride`-th frame of the performance options.frames long
// (options.seed, options.synth) as a photo.
PhotoIdentityEvalResult evaluate_photo_identity_synthetic(const FaceModel& model, const TrackEvalOptions& options,
                                                          int stride);

}  // namespace facecap
