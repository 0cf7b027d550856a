#include "facecap/refine/lighting.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <vector>

#include "facecap/core/statistics.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

ShCoeffs estimate_lighting(const VertexSamples& samples, const Positions& normals, const Positions& albedo,
                           const std::optional<ShCoeffs>& previous, const LightingOptions& options) {
  // Rows rho_ic SH(n_i)^T l = I_ic for the visible vertices.
  std::vector<Eigen::Matrix<double, 9, 1>> basis;
  std::vector<int> index;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (!samples.visible[i]) continue;
    const Vec3f v = to_viewer_frame(Vec3f(normals.col(i)));
    basis.push_back(sh_basis<double>(v.x(), v.y(), v.z()));
    index.push_back(static_cast<int>(i));
  }
  const int n = static_cast<int>(index.size());
  std::vector<double> weight(n, 1.0);
  ShCoeffs l = previous.value_or(ShCoeffs::Zero());
  for (int round = 0; round <= options.robust_iterations; ++round) {
    Eigen::Matrix<double, 9, 9> ata = Eigen::Matrix<double, 9, 9>::Zero();
    Eigen::Matrix<double, 9, 1> atb = Eigen::Matrix<double, 9, 1>::Zero();
    for (int r = 0; r < n; ++r) {
      // The three channels' rows share SH(n_i): one rank-1 update with their
      // summed weights.
      const int i = index[r];
      double rho2 = 0, rho_colour = 0;
      for (int c = 0; c < 3; ++c) {
        const double rho = albedo(c, i);
        rho2 += rho * rho;
        rho_colour += rho * samples.colour(c, i);
      }
      ata.noalias() += (weight[r] * rho2) * (basis[r] * basis[r].transpose());
      atb.noalias() += (weight[r] * rho_colour) * basis[r];
    }
    const double data_weight = ata(0, 0);  // sum of the rows' rho^2
    for (int k = 4; k < 9; ++k) ata(k, k) += options.band2_ridge * data_weight;
    const ShCoeffs prior = previous.value_or(ShCoeffs::Zero());
    const double w = previous ? options.temporal_weight : 1e-6;  // a whisper of ridge on the first frame
    ata.diagonal().array() += w;
    atb += w * prior;
    l = ata.ldlt().solve(atb);
    if (round == options.robust_iterations) break;
    // Huber weights from this round's residuals.
    std::vector<double> residual(n);
    for (int r = 0; r < n; ++r) {
      const int i = index[r];
      const double s = l.dot(basis[r]);
      double e = 0;
      for (int c = 0; c < 3; ++c) e += std::abs(albedo(c, i) * s - samples.colour(c, i));
      residual[r] = e / 3.0;
    }
    const double scale = std::max(1e-4, 1.5 * median(residual));
    for (int r = 0; r < n; ++r) weight[r] = residual[r] <= scale ? 1.0 : scale / residual[r];
  }
  return l;
}

}  // namespace facecap
