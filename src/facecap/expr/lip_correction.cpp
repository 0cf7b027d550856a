#include "facecap/expr/lip_correction.hpp"

#include "facecap/core/box_qp.hpp"

namespace facecap {

std::array<int, 4> key_lip_vertices(const FaceModel& model) {
  const auto& lm = model.landmarks.vertices;
  return {lm[51], lm[62], lm[66], lm[57]};
}

Eigen::MatrixXd lip_basis(const FaceModel& model) {
  const auto verts = key_lip_vertices(model);
  Eigen::MatrixXd rows(12, model.num_expressions());
  for (int k = 0; k < 4; ++k)
    rows.middleRows(3 * k, 3) = model.expression_basis.middleRows(3 * verts[k], 3).cast<double>();
  return rows;
}

Eigen::VectorXf correct_lips(const Eigen::MatrixXd& b, const Eigen::VectorXf& target, const Eigen::VectorXf& source,
                             const LipCorrectionOptions& options) {
  const int n = static_cast<int>(target.size());
  // 1/2 w'Hw + g'w with H = I + alpha B'B, g = -(target + alpha B'B source).
  const Eigen::MatrixXd btb = b.transpose() * b;
  const Eigen::MatrixXd h = Eigen::MatrixXd::Identity(n, n) + options.alpha * btb;
  const Eigen::VectorXd g = -(target.cast<double>() + options.alpha * btb * source.cast<double>());
  Eigen::VectorXd w = target.cast<double>();
  solve_box_qp(h, g, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n), w);
  return w.cast<float>();
}

Eigen::VectorXf window_mean(const std::vector<Eigen::VectorXf>& mapped, const std::vector<float>& confidence) {
  Eigen::VectorXf sum = Eigen::VectorXf::Zero(mapped.front().size());
  float total = 0;
  for (size_t j = 0; j < mapped.size(); ++j) {
    const float c = std::max(1e-4f, confidence[j]);
    sum += c * mapped[j];
    total += c;
  }
  return sum / total;
}

}  // namespace facecap
