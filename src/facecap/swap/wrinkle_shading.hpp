#pragma once
// The target's wrinkles on the swapped face (§6.1.2, eq. 6.1-6.2): the
// target's fine motion since its reference frame (the one whose expression
// is nearest the source's), rotated into the swapped mesh's tangent frames
// and solved for by coating transfer (wrinkle_transfer.hpp), shades the
// render: each pixel is scaled by the SH shading of the wrinkled surface
// over that of the coarse one. The texture already holds the photo's own
// static detail, so only the change is drawn.
#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/core/spherical_harmonics.hpp"
#include "facecap/swap/wrinkle_transfer.hpp"

namespace facecap {

class MeshHierarchy;

class WrinkleShading {
 public:
  // `skin`: the swap's skin mesh (coarse vertex numbering); `source_expression`:
  // the photo's expression weights, which eq. 6.2 measures the target's against.
  WrinkleShading(const TriangleMesh& skin, Eigen::VectorXf source_expression);

  // Scales `render` (CV_32FC3, seen through `window`) by the wrinkles' shading.
  // `hierarchy` and `fine`: the target frame's refined mesh (its finest level
  // and that level's positions); `target_points` and `swapped_points`: the
  // coarse target and swapped faces in camera space. Does nothing where `fine`
  // is not of the finest level. Returns the milliseconds spent setting the
  // transfer up (the first call only: its factorisation), 0 after.
  double shade(const MeshHierarchy& hierarchy, const Positions& fine, const Eigen::VectorXf& target_expression,
               const ShCoeffs& lighting, const Positions& target_points, const Positions& swapped_points,
               const PinholeCamera& window, cv::Mat& render);

 private:
  std::vector<bool> skin_vertices_;
  Eigen::VectorXf source_expression_;
  // Built on the first call.
  std::unique_ptr<CoatingTransfer> coating_;
  std::optional<ExpressionReference> reference_;
  Positions reference_coating_;      // xi_0^T
  std::vector<Triangle> fine_skin_;  // the finest level's skin triangles
};

}  // namespace facecap
