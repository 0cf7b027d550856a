#pragma once
// Lip correction and window smoothing, eq. 5.4:
//   argmin_w ||w - sum_j c_j w_g,j / sum_j c_j||^2 + alpha ||B w - m||^2,  0 <= w <= 1,
// where w_g,j are the mapped weights of the 2k + 1 frames around this one, c_j
// the discriminator's confidence in each, B the expression-basis rows of the
// four key lip vertices (middle of the upper and lower lip, outer and inner
// contour) and m their positions in the source frame. Since the model is
// linear and the identity fixed, B w - m = B (w - w_source). Solved exactly
// with the active-set box QP (core/box_qp.hpp).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "facecap/model/face_model.hpp"

namespace facecap {

// Landmarks 51, 62, 66, 57: upper lip outer and inner, lower lip inner and outer.
std::array<int, 4> key_lip_vertices(const FaceModel& model);

// The 12 x E rows of the expression basis at the key lip vertices (cm).
Eigen::MatrixXd lip_basis(const FaceModel& model);

struct LipCorrectionOptions {
  // eq. 5.4's alpha for positions in centimetres. The paper's 1000 is for
  // FaceWarehouse's mesh unit, about 10 cm (as refine/displacement_solver.hpp
  // reads it): a squared distance there is a hundredth of one in cm, so its
  // 1000 is 10 here. Taken as 1000 in cm, the four points were pinned (0.006
  // mm from the speaker's) and the other weights bent to hold them: the mapped
  // smile of 0.6 came out as 0.4 (`talking_webcam`), where the paper's figure
  // 5.7 shows the points moved toward the speaker's, not onto them. At 10
  // they stay 0.14-0.34 mm from the speaker's on average (README, "The lip
  // weight"). Larger: the lips kept more exactly; 0: no lip correction.
  double alpha = 10.0;
};

// target: the smoothed mapped weights; source: the tracked weights.
Eigen::VectorXf correct_lips(const Eigen::MatrixXd& lip_rows, const Eigen::VectorXf& target,
                             const Eigen::VectorXf& source, const LipCorrectionOptions& options = {});

// Confidence-weighted window mean of mapped weights (eq. 5.4's first term).
Eigen::VectorXf window_mean(const std::vector<Eigen::VectorXf>& mapped, const std::vector<float>& confidence);

}  // namespace facecap
