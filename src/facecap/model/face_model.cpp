#include "facecap/model/face_model.hpp"

#include <algorithm>

#include "facecap/core/error.hpp"

namespace facecap {

int FaceModel::expression_index(const std::string& name) const {
  const auto it = std::find(expression_names.begin(), expression_names.end(), name);
  return it == expression_names.end() ? -1 : static_cast<int>(it - expression_names.begin());
}

Eigen::VectorXf FaceModel::identity_shape(const Eigen::VectorXf& identity, const Region& region) const {
  const Eigen::Index row0 = 3 * region.first_vertex;
  const Eigen::Index rows = 3 * region.num_vertices();
  const Eigen::Index k = std::min<Eigen::Index>(identity.size(), identity_basis.cols());
  Eigen::VectorXf v = neutral.segment(row0, rows);
  if (k > 0) v.noalias() += identity_basis.block(row0, 0, rows, k) * identity.head(k);
  return v;
}

Positions FaceModel::with_expression(const Eigen::VectorXf& identity_shape, const Eigen::VectorXf& expression,
                                     const Region& region) const {
  const Eigen::Index row0 = 3 * region.first_vertex;
  const Eigen::Index rows = 3 * region.num_vertices();
  if (identity_shape.size() != rows) throw Error("identity shape does not match region " + std::string(region.name));
  Eigen::VectorXf v = identity_shape;
  const Eigen::Index k = std::min<Eigen::Index>(expression.size(), expression_basis.cols());
  if (k > 0) v.noalias() += expression_basis.block(row0, 0, rows, k) * expression.head(k);
  return Eigen::Map<const Positions>(v.data(), 3, region.num_vertices());
}

Positions FaceModel::evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression,
                              const Region& region) const {
  return with_expression(identity_shape(identity, region), expression, region);
}

Positions FaceModel::evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression) const {
  const Region all{"all", 0, num_vertices - 1, 0, static_cast<int>(polygons.size()) - 1};
  return evaluate(identity, expression, all);
}

std::vector<Polygon> FaceModel::region_polygons(const Region& region) const {
  if (region.num_polygons() == 0) return {};
  return {polygons.begin() + region.first_polygon, polygons.begin() + region.last_polygon + 1};
}

TriangleMesh FaceModel::region_mesh(const Region& region) const {
  if (region.num_polygons() == 0) throw Error("region " + std::string(region.name) + " has no polygons");
  std::vector<Polygon> local;
  local.reserve(region.num_polygons());
  for (int p = region.first_polygon; p <= region.last_polygon; ++p) {
    Polygon q = polygons[p];
    for (int k = 0; k < q.size(); ++k) {
      q.v[k] -= region.first_vertex;
      if (q.v[k] < 0 || q.v[k] >= region.num_vertices()) throw Error("region polygon leaves its vertex range");
    }
    local.push_back(q);
  }
  return triangulate(local, uvs, region.num_vertices());
}

TriangleMesh FaceModel::full_mesh() const { return triangulate(polygons, uvs, num_vertices); }

}  // namespace facecap
