#pragma once
// Albedo adaptation, eq. 6.3: the adapted albedo keeps the source face's
// albedo differences along every mesh edge and takes the target face's albedo
// on the boundary vertices:
//   min sum_{(i,j) in E} ||(rho_s_i - rho_s_j) - (rho_i - rho_j)||^2,  rho_b = rho_t_b on the boundary.
// Its minimiser is rho = rho_s + h with h harmonic (graph Laplacian L h = 0)
// inside and h = rho_t - rho_s on the boundary, so the solve is one sparse
// Cholesky factorisation of L's interior block and a back-substitution per
// colour channel. The boundary is the face's outline (the longest boundary
// loop): the rims of the eye and mouth holes are left free, since the
// target's colour there is the eye or the mouth interior, not skin; and
// outliers along the outline (hair, a collar) take the outline's median.
//
// The rows are adapted independently: the swap passes each albedo as its
// brightness and hue (brightness_hue.hpp) rather than as B, G, R.
#include <memory>
#include <vector>

#include "facecap/core/mesh.hpp"

namespace facecap {

class AlbedoAdaptation {
 public:
  // The mesh (its open boundary is the Dirichlet boundary) and which boundary
  // vertices carry a target value (an unseen one is left free).
  AlbedoAdaptation(const std::vector<Triangle>& triangles, int num_vertices, const std::vector<bool>& target_known);
  ~AlbedoAdaptation();
  AlbedoAdaptation(AlbedoAdaptation&&) noexcept;
  AlbedoAdaptation& operator=(AlbedoAdaptation&&) noexcept;

  // The offset h (3 x N) that turns the source albedo into the adapted one.
  Positions offset(const Positions& source, const Positions& target) const;

  // Whether `target_known` fixes the same boundary vertices as the one this
  // was built with, so that this adaptation (its factorisation) serves it
  // as one built from it would: the known vertices off the outline do not
  // count.
  bool fixes_the_same(const std::vector<bool>& target_known) const;
  int boundary_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace facecap
