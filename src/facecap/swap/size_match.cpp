#include "facecap/swap/size_match.hpp"

#include "facecap/core/error.hpp"

namespace facecap {

Positions SizeMatch::apply(const Positions& model_points) const {
  Positions out(3, model_points.cols());
  for (Eigen::Index i = 0; i < model_points.cols(); ++i) {
    const Vec3d p = target_centre + scale * (model_points.col(i).cast<double>() - source_centre);
    out.col(i) = p.cast<float>();
  }
  return out;
}

SizeMatch match_size(const Positions& source, const Positions& target) {
  if (source.cols() != target.cols() || source.cols() == 0)
    throw Error("match_size: the two shapes need the same, non-zero number of points");
  SizeMatch m;
  m.source_centre = source.cast<double>().rowwise().mean();
  m.target_centre = target.cast<double>().rowwise().mean();
  double cross = 0, spread = 0;
  for (Eigen::Index i = 0; i < source.cols(); ++i) {
    const Vec3d a = source.col(i).cast<double>() - m.source_centre;
    const Vec3d b = target.col(i).cast<double>() - m.target_centre;
    cross += a.dot(b);
    spread += a.squaredNorm();
  }
  m.scale = spread > 0 ? cross / spread : 1.0;
  return m;
}

}  // namespace facecap
