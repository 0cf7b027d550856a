#pragma once
// The linear face model of DESIGN.md: v = neutral + B_id a + B_exp b
// (the paper's bilinear eq. 3.1 / 4.1 becomes linear on the ICT model).
// Identity weights a ~ N(0, 1) per mode; expression weights b in [0, 1].
#include <string>
#include <vector>

#include "facecap/core/geometry.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/model/regions.hpp"

namespace facecap {

// Which model vertex (or vertices) stands for each of the 68 iBUG landmarks.
struct LandmarkMap {
  std::vector<int> vertices;         // 68 vertex indices in iBUG order
  std::vector<int> rigid_landmarks;  // landmark numbers of idx_to_rigid_landmark_idx
  // Jawline candidates along the silhouette (FACTS.md). The short lists stand
  // for iBUG 0-7 (right) and 9-16 (left), outermost first; the extended lists
  // interleave extra vertices between them.
  std::vector<int> jaw_right;
  std::vector<int> jaw_left;
  std::vector<int> jaw_right_extended;
  std::vector<int> jaw_left_extended;
};

struct FaceModel {
  int num_vertices = 0;
  Eigen::VectorXf neutral;           // 3N: x0 y0 z0 x1 ...
  Eigen::MatrixXf identity_basis;    // 3N x num_identity: identity_i - neutral
  Eigen::MatrixXf expression_basis;  // 3N x num_expressions: expression_j - neutral
  std::vector<std::string> expression_names;
  std::vector<Polygon> polygons;
  std::vector<Vec2f> uvs;
  LandmarkMap landmarks;

  int num_identity() const { return static_cast<int>(identity_basis.cols()); }
  int num_expressions() const { return static_cast<int>(expression_basis.cols()); }
  int expression_index(const std::string& name) const;  // -1 when absent

  // Vertex positions (model space, cm) of the whole head.
  Positions evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression) const;
  // The same for the vertices of one region only (positions are region-local:
  // column i is vertex region.first_vertex + i). Shorter weight vectors use the
  // leading modes; the rest are zero.
  Positions evaluate(const Eigen::VectorXf& identity, const Eigen::VectorXf& expression, const Region& region) const;
  // neutral + B_id a for a region: the identity shape, evaluated once per video.
  Eigen::VectorXf identity_shape(const Eigen::VectorXf& identity, const Region& region) const;
  // An identity shape of `region` (from identity_shape) with expression
  // weights added: evaluate() without recomputing the identity part.
  Positions with_expression(const Eigen::VectorXf& identity_shape, const Eigen::VectorXf& expression,
                            const Region& region) const;

  // A region's polygons as the model lists them (the model's vertex indices,
  // which are the region's own for the face, whose vertices come first).
  std::vector<Polygon> region_polygons(const Region& region) const;
  // Triangle mesh of a region's polygons, re-indexed to region-local vertices.
  TriangleMesh region_mesh(const Region& region) const;
  // Triangle mesh of the whole head (all polygons), in global vertex indices.
  TriangleMesh full_mesh() const;
};

}  // namespace facecap
