#include "facecap/fit/frame_energy.hpp"

#include <cmath>

namespace facecap {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}

void set_landmark_observations(const Landmarks& observed, const FitWeights& w, const Eigen::Vector2d& principal_point,
                               std::array<LandmarkTerm, 68>& terms) {
  const double scale = std::max(1.0, double(outer_eye_distance(observed))) / 100.0;
  for (int i = 0; i < 68; ++i) {
    LandmarkTerm& t = terms[i];
    t.observed = observed[i].cast<double>();
    t.principal_point = principal_point;
    t.inv_sigma = 1.0 / (w.sigma_landmark * scale * (i <= 16 ? w.jaw_sigma_factor : 1.0));
  }
}

void set_landmark_correspondences(const LandmarkBasis& basis, const Correspondences& correspondences,
                                  std::array<LandmarkTerm, 68>& terms) {
  for (int i = 0; i < 68; ++i) {
    const Correspondence& c = correspondences[i];
    const int sa = basis.slot(c.a), sb = basis.slot(c.b);
    const double wa = 1.0 - c.t, wb = c.t;
    LandmarkTerm& t = terms[i];
    // The model is linear, so a point between two vertices has the blended rows.
    t.neutral = wa * basis.neutral.col(sa) + wb * basis.neutral.col(sb);
    t.identity_rows = wa * basis.identity.middleRows(3 * sa, 3) + wb * basis.identity.middleRows(3 * sb, 3);
    t.expression_rows = wa * basis.expression.middleRows(3 * sa, 3) + wb * basis.expression.middleRows(3 * sb, 3);
  }
}

FrameEnergy::FrameEnergy(const LandmarkBasis& basis, const FitWeights& weights, const Landmarks& observed,
                         const Eigen::Vector2d& principal_point, const Eigen::VectorXd& identity, double focal,
                         const FrameParameters* previous, const FrameParameters* next)
    : basis_(basis),
      weights_(weights),
      identity_(identity),
      focal_(focal),
      num_expressions_(static_cast<int>(basis.expression.cols())) {
  set_landmark_observations(observed, weights, principal_point, terms_);
  for (int i = 0; i < 68; ++i) {
    costs_.push_back(std::make_unique<LandmarkCost>(&terms_[i], static_cast<int>(identity.size()), num_expressions_));
  }
  auto add_prior = [&](int index, double mean, double sigma) {
    prior_index_.push_back(index);
    prior_mean_.push_back(mean);
    prior_inv_sigma_.push_back(1.0 / sigma);
  };
  for (int k = 0; k < num_expressions_; ++k) add_prior(frame_block::kExpression + k, 0.0, weights.sigma_expression);
  for (const FrameParameters* neighbour : {previous, next}) {
    if (neighbour == nullptr) continue;
    for (int k = 0; k < 3; ++k) {
      add_prior(frame_block::kRotation + k, neighbour->values[frame_block::kRotation + k],
                weights.sigma_temporal_rotation_deg * kDegToRad);
      add_prior(frame_block::kTranslation + k, neighbour->values[frame_block::kTranslation + k],
                weights.sigma_temporal_translation_cm);
    }
    for (int k = 0; k < num_expressions_; ++k) {
      add_prior(frame_block::kExpression + k, neighbour->values[frame_block::kExpression + k],
                weights.sigma_temporal_expression);
    }
  }
  fixed_priors_ = prior_index_.size();
  rows_ = 2 * 68 + static_cast<int>(prior_index_.size());
  update_shaped();
}

void FrameEnergy::set_expression_targets(const std::vector<std::pair<int, double>>& targets, double sigma) {
  prior_index_.resize(fixed_priors_);
  prior_mean_.resize(fixed_priors_);
  prior_inv_sigma_.resize(fixed_priors_);
  for (const auto& [k, target] : targets) {
    prior_index_.push_back(frame_block::kExpression + k);
    prior_mean_.push_back(target);
    prior_inv_sigma_.push_back(1.0 / sigma);
  }
  rows_ = 2 * 68 + static_cast<int>(prior_index_.size());
}

void FrameEnergy::set_correspondences(const Correspondences& correspondences) {
  set_landmark_correspondences(basis_, correspondences, terms_);
  update_shaped();
}

void FrameEnergy::set_shared(const Eigen::VectorXd& identity, double focal) {
  identity_ = identity;
  focal_ = focal;
  update_shaped();
}

void FrameEnergy::update_shaped() {
  const Eigen::Map<const Eigen::VectorXd> a(identity_.data(), identity_.size());
  for (int i = 0; i < 68; ++i) shaped_[i] = identity_shaped_point(terms_[i], a);
}

double FrameEnergy::landmark_block(int i, const FrameParameters& x, double* residual, double* jacobian_pose,
                                   double* jacobian_expression, double* jacobian_identity,
                                   double* jacobian_focal) const {
  bool in_front = false;
  if (jacobian_identity == nullptr) {
    // The identity's part of the model point is fixed here (shaped_).
    const LandmarkTerm& t = terms_[i];
    const Eigen::Map<const Eigen::VectorXd> w(x.values.data() + frame_block::kExpression, num_expressions_);
    Eigen::Vector3d point = shaped_[i];
    point.noalias() += t.expression_rows * w;
    in_front = project_landmark(t, point, x.values.data(), focal_, residual, jacobian_pose, jacobian_expression,
                                nullptr, jacobian_focal);
  } else {
    const double focal = focal_;
    const double* params[4] = {x.values.data(), x.values.data() + frame_block::kExpression, identity_.data(), &focal};
    double* jacobians[4] = {jacobian_pose, jacobian_expression, jacobian_identity, jacobian_focal};
    in_front = costs_[i]->Evaluate(params, residual, jacobian_pose ? jacobians : nullptr);
  }
  if (!in_front) residual[0] = residual[1] = 1e6;  // behind the camera
  return residual[0] * residual[0] + residual[1] * residual[1];
}

double FrameEnergy::cost(const FrameParameters& x) const {
  const double k2 = weights_.huber_scale * weights_.huber_scale;
  double total = 0.0;
  double res[2];
  for (int i = 0; i < 68; ++i) {
    const double s = landmark_block(i, x, res, nullptr, nullptr);
    total += s <= k2 ? s : 2.0 * weights_.huber_scale * std::sqrt(s) - k2;  // Huber rho(s)
  }
  for (size_t p = 0; p < prior_index_.size(); ++p) {
    const double r = (x.values[int(prior_index_[p])] - prior_mean_[p]) * prior_inv_sigma_[p];
    total += r * r;
  }
  return 0.5 * total + weights_.expression_l1 * x.expression().sum();
}

double FrameEnergy::linearize(const FrameParameters& x, Eigen::VectorXd& r, Eigen::MatrixXd& jacobian,
                              Eigen::MatrixXd* shared) const {
  const int cols = block_size();
  const int ni = static_cast<int>(identity_.size());
  r.resize(rows_);
  jacobian.setZero(rows_, cols);
  if (shared != nullptr) shared->setZero(rows_, ni + 1);
  Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor> ja(2, ni);
  Eigen::Vector2d jf;
  const double k = weights_.huber_scale;
  double total = 0.0;
  double res[2];
  Eigen::Matrix<double, 2, 6, Eigen::RowMajor> jp;
  Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor> jw(2, num_expressions_);
  for (int i = 0; i < 68; ++i) {
    const double s =
        landmark_block(i, x, res, jp.data(), jw.data(), shared ? ja.data() : nullptr, shared ? jf.data() : nullptr);
    // Huber as iteratively reweighted least squares: rows scaled by sqrt(rho'(s)).
    double scale = 1.0;
    if (s > k * k) {
      scale = std::sqrt(k / std::sqrt(s));
      total += 2.0 * k * std::sqrt(s) - k * k;
    } else {
      total += s;
    }
    for (int c = 0; c < 2; ++c) {
      r[2 * i + c] = scale * res[c];
      jacobian.block(2 * i + c, 0, 1, 6) = scale * jp.row(c);
      jacobian.block(2 * i + c, frame_block::kExpression, 1, num_expressions_) = scale * jw.row(c);
      if (shared != nullptr) {
        shared->block(2 * i + c, 0, 1, ni) = scale * ja.row(c);
        (*shared)(2 * i + c, ni) = scale * jf[c];
      }
    }
  }
  for (size_t p = 0; p < prior_index_.size(); ++p) {
    const int row = 136 + static_cast<int>(p);
    const int index = static_cast<int>(prior_index_[p]);
    r[row] = (x.values[index] - prior_mean_[p]) * prior_inv_sigma_[p];
    jacobian(row, index) = prior_inv_sigma_[p];
    total += r[row] * r[row];
  }
  return 0.5 * total + weights_.expression_l1 * x.expression().sum();
}

}  // namespace facecap
