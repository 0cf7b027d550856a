#pragma once
// The size of a face seen through landmarks, and the bias of the identity
// solve's answer to it.
//
// A pinhole camera maps a face scaled by s at s times the distance to the same
// image, so landmarks fix the identity's shape but hardly its size. Write the
// fitted face as neutral + B a = B (a + m) + (what B cannot express), with m
// the least-squares coefficients of the (centred) neutral face in the identity
// basis B. Scaling the face is then moving b = a + m along its ray: b = r d.
// Along that ray the landmarks are nearly flat (ICT: 0.01 mm of landmark
// residual per 1 % of size), so the joint MAP of the identity solve stops
// where the prior exp(-|a|^2 / 2) = exp(-|r d - m|^2 / 2) peaks, r = d.m.
// That is the mode of the joint posterior, not where its mass is: the set of
// identities the landmarks allow is a cone around d whose cross-section grows
// as r^k, k the number of directions across the ray that the landmarks
// determine, so the posterior of the length is
//   p(r) ~ r^k exp(-|r d - m|^2 / 2),
// whose mode is r* = (d.m + sqrt((d.m)^2 + 4 k)) / 2. The landmarks determine
// directions partly; k counts each by its data precision over its posterior
// precision (IdentitySolveReport::effective_modes). With ICT's |m| = 37 and
// all 49 directions across the ray determined, r* is 3.5 % longer: the MAP
// face is that much too small. This class moves the fitted identity from the
// one to the other, b -> (r* / d.m) b, keeping whatever the landmarks did say
// about the size.
//
// The factor comes from m over the face region (its size is what is
// corrected). The move uses m over the vertices the landmarks are fitted to,
// so that those scale as exactly as the modes allow and the fit to the
// landmarks stays where it was: synthetic sweeps (`eval track --synthetic 90`,
// seeds 1 / 7 / 9) turned heads with rotation errors 0.80 / 0.98 / 0.79 deg
// before the correction, 0.85 / 1.03 / 0.85 with the move over the face region
// and 0.76 / 0.93 / 0.74 with this one, at the same size.
#include <Eigen/Core>
#include <vector>

#include "facecap/model/face_model.hpp"

namespace facecap {

class IdentitySizeCorrection {
 public:
  // identity_modes: the leading modes the fit solves for (K);
  // fitted_vertices: the model vertices the landmarks are fitted to (empty:
  // the face region).
  IdentitySizeCorrection(const FaceModel& model, int identity_modes, const std::vector<int>& fitted_vertices = {});

  // The factor c >= 1 by which the identity's length a + m grows, with
  // `determined` directions across the ray determined by the landmarks (k
  // above; at most modes - 1).
  double factor(const Eigen::VectorXd& identity, double determined) const;
  // c (a + m) - m: the same shape, c times larger.
  Eigen::VectorXd scale(const Eigen::VectorXd& identity, double c) const;
  // scale(identity, factor(identity, determined)).
  Eigen::VectorXd apply(const Eigen::VectorXd& identity, double determined) const;

  const Eigen::VectorXd& mean_coefficients() const { return mean_; }

 private:
  Eigen::VectorXd mean_;         // m over the face region
  Eigen::VectorXd fitted_mean_;  // m over the vertices the landmarks are fitted to
};

}  // namespace facecap
