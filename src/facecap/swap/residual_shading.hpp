#pragma once
// What the target's SH lighting leaves unexplained, low-pass over the face.
// The SH irradiance of eq. 4.9 depends on the normal alone: light that falls
// off toward the chin, a lamp near the face, the broad shadow of the brow or
// the nose change the target face in ways no such lighting can fit, and a
// new face rendered under it alone (eq. 6.7) keeps the shading pattern of
// the appearance frames. Here each target vertex seen squarely gives the
// ratio, per channel, of its observed colour to its own albedo (the
// appearance frames' mean) shaded by this frame's lighting; the ratios,
// splatted into a coarse UV grid and blurred to a low-pass field some
// centimetres wide, scale the new face texel by texel (the two meshes share
// their UVs).
//
// The scale is the choice that matters: at a few millimetres the field
// copies the target's own look (its lips, its folds, tracking errors) onto
// the new face, which a self-swap rewards and a real swap shows as a ghost.
#include <opencv2/core.hpp>
#include <span>
#include <vector>

#include "facecap/core/geometry.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/swap/lit_vertices.hpp"

namespace facecap {

struct ResidualShadingOptions {
  float min_facing = 0.5f;    // vertices whose normal is within 60 degrees of the view ray
  float min_seen = 0.05f;     // albedo weight a vertex needs (the appearance frames saw it)
  float low_pass_mm = 20.0f;  // Gaussian sigma of the field, on the face
  float max_gain = 1.25f;     // gains are clamped to [1 / max_gain, max_gain]
};

class ResidualShading {
 public:
  // `mesh`: triangles with UVs; `reference`: a face shape on it (cm) that
  // gives the millimetres per UV unit.
  ResidualShading(const TriangleMesh& mesh, const Positions& reference, ResidualShadingOptions options = {});

  // The gain field (CV_32FC3, BGR, grid_size() square over UV [0, 1]^2, row
  // 0 at v = 1 like the face texture), each channel of mean 1 over the lit
  // vertices: the overall level and colour are the SH lighting's and
  // light_colour()'s business. All ones where fewer than 50 vertices are
  // lit. `lit`: the target face's vertices this frame shows
  // (lit_vertices()); `albedo`: 3 x N BGR in [0, 1].
  cv::Mat gains(std::span<const LitVertex> lit, const Positions& albedo) const;

  int grid_size() const { return grid_; }
  double mm_per_uv() const { return mm_per_uv_; }

 private:
  ResidualShadingOptions options_;
  std::vector<Vec2f> vertex_uvs_;
  double mm_per_uv_ = 0;
  int grid_ = 0;
  double sigma_texels_ = 0;
};

}  // namespace facecap
