#include "facecap/refine/displacement_solver.hpp"

#include <cmath>

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// Gradient of s(v) = l^T SH(v) with respect to the viewer-frame normal v.
inline Vec3f sh_gradient(const ShCoeffs& l, const Vec3f& v) {
  return {float(l[1] + l[4] * v.y() + l[5] * v.z() + 2 * l[7] * v.x()),
          float(l[2] + l[4] * v.x() + l[6] * v.z() - 2 * l[7] * v.y()),
          float(l[3] + l[5] * v.x() + l[6] * v.y() + 6 * l[8] * v.z())};
}

// The linearisation of one Gauss-Newton step.
struct Linearisation {
  Eigen::VectorXf shading;        // s_i
  Eigen::VectorXf self;           // d s_i / d d_i
  Eigen::VectorXf ring;           // d s_i / d d_q for the ring entries of i
  Eigen::VectorXf weight;         // W_i = sum_c rho_ic^2 (0 when not visible)
  Eigen::VectorXf data_residual;  // sum_c rho_ic (rho_ic s_i - I_ic)
  Eigen::VectorXf vertex_cost;    // sum_c (rho_ic s_i - I_ic)^2
  double data_cost = 0;
};

// The regularisers' weights for d in centimetres.
DisplacementOptions scaled(DisplacementOptions o) {
  const double k = 1.0 / (o.length_unit_cm * o.length_unit_cm);
  o.weights.smooth *= k;
  o.weights.hierarchy *= k;
  o.weights.temporal *= k;
  o.weights.coarse *= k;
  return o;
}

class Solver {
 public:
  Solver(const DisplacementProblem& p, const DisplacementOptions& o) : p_(p), o_(scaled(o)), lv_(*p.level) {
    n_ = lv_.num_vertices;
    free_.resize(n_);
    // Dirichlet: d = 0 on the boundary, and outside the active set.
    for (int i = 0; i < n_; ++i) {
      free_[i] = (lv_.boundary[i] || (!p.active.empty() && !p.active[i])) ? 0.0f : 1.0f;
      if (free_[i] > 0) active_.push_back(i);
    }
    // Residuals that involve a free vertex: the free vertices and their rings.
    std::vector<bool> touched(n_, false);
    for (int i : active_) {
      touched[i] = true;
      for (int s = lv_.rings.offsets[i]; s < lv_.rings.offsets[i + 1]; ++s) touched[lv_.rings.indices[s]] = true;
    }
    for (int i = 0; i < n_; ++i)
      if (touched[i]) touched_.push_back(i);
    diag_const_ = float(o.weights.coarse + (p.previous.size() ? o.weights.temporal : 0.0) +
                        (p.prolonged.size() ? o.weights.hierarchy : 0.0));
  }

  void linearise(const Eigen::VectorXf& d, Linearisation& lin) const {
    lin.shading.resize(n_);
    lin.self.resize(n_);
    lin.ring.resize(lv_.rings.indices.size());
    lin.weight.resize(n_);
    lin.data_residual.resize(n_);
    lin.vertex_cost.setZero(n_);
    lin.shading.setZero();
    lin.self.setZero();
    lin.ring.setZero();
    lin.weight.setZero();
    lin.data_residual.setZero();
    const Positions pos = displaced_positions(p_.base, p_.base_normals, d);
    const int nt = static_cast<int>(touched_.size());
    parallel_for(
        nt,
        [&](int b, int e) {
          for (int ti = b; ti < e; ++ti) {
            const int i = touched_[ti];
            const Vec3f pi = pos.col(i);
            Vec3f m = Vec3f::Zero();
            Vec3f dm_self = Vec3f::Zero();
            const int ro = lv_.rings.offsets[i];
            const int deg = lv_.rings.degree(i);
            Vec3f dm_ring[32];
            for (int s = 0; s < std::min(deg, 32); ++s) dm_ring[s] = Vec3f::Zero();
            for (int c = lv_.corner_offsets[i]; c < lv_.corner_offsets[i + 1]; ++c) {
              const auto& [j, k] = lv_.corners[c];
              const auto& [sj, sk] = lv_.corner_slots[c];
              const Vec3f a = pos.col(j) - pi, bvec = pos.col(k) - pi;
              m += a.cross(bvec);
              // d/dd_i (a x b) = n_i x (a - b); d/dd_j = n_j x b; d/dd_k = a x n_k.
              dm_self += Vec3f(p_.base_normals.col(i)).cross(a - bvec);
              if (sj >= 0 && sj < 32) dm_ring[sj] += Vec3f(p_.base_normals.col(j)).cross(bvec);
              if (sk >= 0 && sk < 32) dm_ring[sk] += a.cross(Vec3f(p_.base_normals.col(k)));
            }
            const float len = m.norm();
            const bool visible = p_.samples->visible[i] && len > 0;
            if (len <= 0) {
              lin.shading[i] = 0;
              lin.self[i] = 0;
              for (int s = 0; s < deg; ++s) lin.ring[ro + s] = 0;
              lin.weight[i] = 0;
              lin.data_residual[i] = 0;
              continue;
            }
            const Vec3f nhat = m / len;
            const Vec3f v(nhat.x(), -nhat.y(), -nhat.z());  // viewer frame for SH
            const Vec3f gv = sh_gradient(p_.lighting, v);
            const Vec3f g(gv.x(), -gv.y(), -gv.z());  // back to the camera frame
            // ds/dm = g^T (I - n n^T) / |m|
            const Vec3f dsdm = (g - nhat * nhat.dot(g)) / len;
            const float s = float(sh_shade(p_.lighting, double(v.x()), double(v.y()), double(v.z())));
            lin.shading[i] = s;
            lin.self[i] = dsdm.dot(dm_self);
            for (int sl = 0; sl < deg; ++sl) lin.ring[ro + sl] = sl < 32 ? dsdm.dot(dm_ring[sl]) : 0.0f;
            if (visible) {
              float w = 0, r = 0, e2 = 0;
              for (int c = 0; c < 3; ++c) {
                const float rho = p_.albedo(c, i);
                const float res = rho * s - p_.samples->colour(c, i);
                w += rho * rho;
                r += rho * res;
                e2 += res * res;
              }
              // Huber on the vertex's residual, as reweighted least squares.
              const float k = float(o_.data_huber);
              float robust = 1.0f;
              if (k > 0 && e2 > k * k) {
                const float e = std::sqrt(e2);
                robust = k / e;
                lin.vertex_cost[i] = 2 * k * e - k * k;
              } else {
                lin.vertex_cost[i] = e2;
              }
              lin.weight[i] = robust * w;
              lin.data_residual[i] = robust * r;
            } else {
              lin.weight[i] = 0;
              lin.data_residual[i] = 0;
            }
          }
        },
        512);
    lin.data_cost = lin.vertex_cost.cast<double>().sum();
  }

  // The row products over the touched vertices: lx = L x for the uniform
  // graph Laplacian L = I - A / r and, given a linearisation, wgx = W G x
  // (G_iq = d s_i / d d_q). Entries elsewhere are left as they were.
  template <bool kWithData>
  void apply_rows(const Linearisation* lin, const Eigen::VectorXf& x, Eigen::VectorXf* wgx, Eigen::VectorXf& lx) const {
    const int nt = static_cast<int>(touched_.size());
    parallel_for(
        nt,
        [&](int b, int e) {
          for (int ti = b; ti < e; ++ti) {
            const int i = touched_[ti];
            const int deg = lv_.rings.degree(i);
            float g = 0;
            if constexpr (kWithData) g = lin->self[i] * x[i];
            float mean = 0;
            for (int s = lv_.rings.offsets[i]; s < lv_.rings.offsets[i + 1]; ++s) {
              const float xs = x[lv_.rings.indices[s]];
              if constexpr (kWithData) g += lin->ring[s] * xs;
              mean += xs;
            }
            if constexpr (kWithData) (*wgx)[i] = g * lin->weight[i];
            lx[i] = deg > 0 ? x[i] - mean / deg : 0.0f;
          }
        },
        1024);
  }
  // y = L x, zero where no free vertex reaches.
  void apply_l(const Eigen::VectorXf& x, Eigen::VectorXf& y) const {
    y.setZero(n_);
    apply_rows<false>(nullptr, x, nullptr, y);
  }
  // The column products over the free vertices, zero elsewhere:
  //   y = G^T u + (w3 L^T v + c x)
  // (gathers: entry q collects from q and its ring).
  void apply_columns(const Linearisation& lin, const Eigen::VectorXf& u, const Eigen::VectorXf& v, float c,
                     const Eigen::VectorXf& x, Eigen::VectorXf& y) const {
    y.setZero(n_);
    const float smooth = float(o_.weights.smooth);
    const int na = static_cast<int>(active_.size());
    parallel_for(
        na,
        [&](int b, int e) {
          for (int ai = b; ai < e; ++ai) {
            const int q = active_[ai];
            float data = lin.self[q] * u[q];
            float lap = lv_.rings.degree(q) > 0 ? v[q] : 0.0f;
            for (int s = lv_.rings.offsets[q]; s < lv_.rings.offsets[q + 1]; ++s) {
              const int i = lv_.rings.indices[s];
              const int back = lv_.ring_transpose[s];
              if (back >= 0) data += lin.ring[back] * u[i];
              lap -= v[i] / lv_.rings.degree(i);
            }
            y[q] = data + (smooth * lap + c * x[q]);
          }
        },
        1024);
  }

  // (J^T J) x restricted to free vertices: the row pass, then the column pass
  // (one wake of the workers each).
  void apply_normal(const Linearisation& lin, const Eigen::VectorXf& x, Eigen::VectorXf& y, Eigen::VectorXf& wgx,
                    Eigen::VectorXf& lx) const {
    wgx.resize(n_);  // read only at touched vertices, which the row pass writes
    lx.resize(n_);
    apply_rows<true>(&lin, x, &wgx, lx);
    apply_columns(lin, wgx, lx, diag_const_, x, y);
  }

  double cost(const Eigen::VectorXf& d, const Linearisation& lin) const {
    Eigen::VectorXf ld;
    apply_l(d, ld);
    double c = lin.data_cost + o_.weights.smooth * ld.squaredNorm() + o_.weights.coarse * d.squaredNorm();
    if (p_.prolonged.size()) c += o_.weights.hierarchy * (d - p_.prolonged).squaredNorm();
    if (p_.previous.size()) c += o_.weights.temporal * (d - p_.previous).squaredNorm();
    return c;
  }

  DisplacementReport run(Eigen::VectorXf& d) const {
    DisplacementReport rep;
    d.array() *= free_.array();
    Linearisation lin;
    linearise(d, lin);
    double current = cost(d, lin);
    rep.initial_cost = current;
    Eigen::VectorXf grad, t1, t2, r, z, p, ap, x;
    for (rep.steps = 0; rep.steps < o_.gauss_newton_steps; ++rep.steps) {
      // Gradient J^T r of the whole energy.
      apply_l(d, t1);
      apply_columns(lin, lin.data_residual, t1, float(o_.weights.coarse), d, grad);
      if (p_.prolonged.size()) grad += float(o_.weights.hierarchy) * (d - p_.prolonged);
      if (p_.previous.size()) grad += float(o_.weights.temporal) * (d - p_.previous);
      grad.array() *= free_.array();
      // Jacobi preconditioner: diag(J^T J).
      Eigen::VectorXf diag = Eigen::VectorXf::Ones(n_);
      const int na = static_cast<int>(active_.size());
      parallel_for(
          na,
          [&](int b, int e) {
            for (int ai = b; ai < e; ++ai) {
              const int q = active_[ai];
              float dd = lin.weight[q] * lin.self[q] * lin.self[q];
              float lap = lv_.rings.degree(q) > 0 ? 1.0f : 0.0f;
              for (int s = lv_.rings.offsets[q]; s < lv_.rings.offsets[q + 1]; ++s) {
                const int i = lv_.rings.indices[s];
                const int back = lv_.ring_transpose[s];
                if (back >= 0) {
                  const float g = lin.ring[back];
                  dd += lin.weight[i] * g * g;
                }
                const float deg = float(lv_.rings.degree(i));
                lap += 1.0f / (deg * deg);
              }
              diag[q] = dd + float(o_.weights.smooth) * lap + diag_const_;
            }
          },
          1024);
      // Algorithm 2: PCG from x0 = 0 on (J^T J) x = -J^T r.
      x.setZero(n_);
      r = -grad;
      z = r.cwiseQuotient(diag);
      p = z;
      double rz = r.dot(z);
      for (int k = 0; k < o_.pcg_iterations && rz > 1e-30; ++k) {
        apply_normal(lin, p, ap, t1, t2);
        const double pap = p.dot(ap);
        if (pap <= 0) break;
        const float alpha = float(rz / pap);
        x += alpha * p;
        r -= alpha * ap;
        z = r.cwiseQuotient(diag);
        const double rz_new = r.dot(z);
        p = z + float(rz_new / rz) * p;
        rz = rz_new;
      }
      // Gauss-Newton step; halved if it does not lower the energy.
      Eigen::VectorXf trial;
      Linearisation trial_lin;
      double trial_cost = current;
      float scale = 1.0f;
      for (int h = 0; h < 4; ++h, scale *= 0.5f) {
        trial = d + scale * x;
        linearise(trial, trial_lin);
        trial_cost = cost(trial, trial_lin);
        if (trial_cost < current) break;
      }
      if (!(trial_cost < current)) break;
      d = trial;
      lin = std::move(trial_lin);
      current = trial_cost;
    }
    rep.final_cost = current;
    return rep;
  }

 private:
  const DisplacementProblem& p_;
  const DisplacementOptions o_;
  const MeshLevel& lv_;
  int n_ = 0;
  Eigen::VectorXf free_;
  std::vector<int> active_;   // free vertices
  std::vector<int> touched_;  // free vertices and their rings
  float diag_const_ = 0;
};

}  // namespace

Positions displaced_positions(const Positions& base, const Positions& normals, const Eigen::VectorXf& d) {
  Positions out = base;
  for (Eigen::Index i = 0; i < base.cols(); ++i) out.col(i) += d[i] * normals.col(i);
  return out;
}

DisplacementReport solve_displacements(const DisplacementProblem& problem, Eigen::VectorXf& d,
                                       const DisplacementOptions& options) {
  const Solver solver(problem, options);
  return solver.run(d);
}

}  // namespace facecap
