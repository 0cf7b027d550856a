#include "facecap/refine/displacement_solver.hpp"

#include <chrono>
#include <cmath>

#include "facecap/core/parallel.hpp"
#include "facecap/core/stopwatch.hpp"
#include "facecap/refine/displacement_graph.hpp"

namespace facecap {

namespace {

// Gradient of s(v) = l^T SH(v) with respect to the viewer-frame normal v.
inline Vec3f sh_gradient(const ShCoeffs& l, const Vec3f& v) {
  return {float(l[1] + l[4] * v.y() + l[5] * v.z() + 2 * l[7] * v.x()),
          float(l[2] + l[4] * v.x() + l[6] * v.z() - 2 * l[7] * v.y()),
          float(l[3] + l[5] * v.x() + l[6] * v.y() + 6 * l[8] * v.z())};
}

// The linearisation of one Gauss-Newton step, over the touched vertices.
struct Linearisation {
  Eigen::VectorXf self;           // d s_t / d d_t
  Eigen::VectorXf jac;            // d s_t / d d_q per row entry (t, q)
  Eigen::VectorXf jac_by_column;  // the same per column entry (q, t) (0 where t's ring lacks q)
  Eigen::VectorXf weight;         // W_t = sum_c rho_tc^2 (0 when not visible)
  Eigen::VectorXf data_residual;  // sum_c rho_tc (rho_tc s_t - I_tc)
  double data_cost = 0;           // sum of the (Huber) vertex costs
};

// Vertices per block of the PCG's parallel passes and their sums (fixed, so
// that the sums do not depend on the thread count).
constexpr int kBlock = 2048;

class Solver {
 public:
  Solver(const DisplacementProblem& p, const DisplacementOptions& o)
      : p_(p), o_(weights_in_centimetres(o)), lv_(*p.level), g_(lv_, free_vertices(p)) {
    positions_ = p.base;
    const int nf = g_.num_free;
    // The fixed vertices' share of E_hier and E_temp (d = 0 there): constant,
    // kept so that the reported energies are the whole energy.
    const auto free_part = [&](const Eigen::VectorXf& full, Eigen::VectorXf& part, double& fixed_cost) {
      if (full.size() == 0) return;
      part.resize(nf);
      for (int a = 0; a < nf; ++a) part[a] = full[g_.global[a]];
      fixed_cost = double(full.squaredNorm()) - double(part.squaredNorm());
    };
    free_part(p.prolonged, prolonged_, prolonged_fixed_);
    free_part(p.previous, previous_, previous_fixed_);
    diag_const_ = float(o_.weights.coarse + (p.previous.size() ? o_.weights.temporal : 0.0) +
                        (p.prolonged.size() ? o_.weights.hierarchy : 0.0));
  }

  void linearise(const Eigen::VectorXf& d, Linearisation& lin) {
    const int nt = g_.touched();
    lin.self.resize(nt);
    lin.jac.resize(static_cast<Eigen::Index>(g_.row_cols.size()));
    lin.weight.resize(nt);
    lin.data_residual.resize(nt);
    vertex_cost_.resize(nt);
    // The displaced positions, once: each enters the normals of its whole ring.
    for (int a = 0; a < g_.num_free; ++a) {
      const int i = g_.global[a];
      positions_.col(i) = p_.base.col(i) + d[a] * p_.base_normals.col(i);
    }
    parallel_for(
        nt,
        [&](int b, int e) {
          for (int t = b; t < e; ++t) linearise_vertex(t, lin);
        },
        512);
    lin.data_cost = vertex_cost_.cast<double>().sum();
    // The column passes read the Jacobian in column order: gathered once
    // here instead of through col_entries in each of the PCG's products.
    lin.jac_by_column.resize(static_cast<Eigen::Index>(g_.col_rows.size()));
    parallel_for(
        g_.num_free,
        [&](int b, int e) {
          for (int k = g_.col_offsets[b]; k < g_.col_offsets[e]; ++k) {
            const int entry = g_.col_entries[k];
            lin.jac_by_column[k] = entry >= 0 ? lin.jac[entry] : 0.0f;
          }
        },
        kBlock);
  }

  // The row products over the touched vertices: lx = L x for the uniform
  // graph Laplacian L = I - A / r and, with data, wgx = W G x
  // (G_tq = d s_t / d d_q).
  template <bool kWithData>
  void apply_rows(const Linearisation* lin, const Eigen::VectorXf& x, Eigen::VectorXf* wgx, Eigen::VectorXf& lx) const {
    const int nt = g_.touched();
    lx.resize(nt);
    if constexpr (kWithData) wgx->resize(nt);
    parallel_for(
        nt,
        [&](int b, int e) {
          for (int t = b; t < e; ++t) {
            const float xt = t < g_.num_free ? x[t] : 0.0f;
            float g = 0, sum = 0;
            if constexpr (kWithData) g = lin->self[t] * xt;
            for (int k = g_.row_offsets[t]; k < g_.row_offsets[t + 1]; ++k) {
              const float xs = x[g_.row_cols[k]];
              if constexpr (kWithData) g += lin->jac[k] * xs;
              sum += xs;
            }
            if constexpr (kWithData) (*wgx)[t] = g * lin->weight[t];
            lx[t] = g_.inv_degree[t] > 0 ? xt - sum * g_.inv_degree[t] : 0.0f;
          }
        },
        1024);
  }
  // The column products over the free vertices:
  //   y = G^T u + (w3 L^T v + c x)
  // (gathers: entry q collects from q and its ring). Returns x . y.
  double apply_columns(const Linearisation& lin, const Eigen::VectorXf& u, const Eigen::VectorXf& v, float c,
                       const Eigen::VectorXf& x, Eigen::VectorXf& y) const {
    const int nf = g_.num_free;
    y.resize(nf);
    const float smooth = float(o_.weights.smooth);
    return parallel_sum(
        nf,
        [&](int b, int e) {
          double xy = 0;
          for (int a = b; a < e; ++a) {
            float data = lin.self[a] * u[a];
            float lap = g_.inv_degree[a] > 0 ? v[a] : 0.0f;
            for (int k = g_.col_offsets[a]; k < g_.col_offsets[a + 1]; ++k) {
              const int t = g_.col_rows[k];
              data += lin.jac_by_column[k] * u[t];
              lap -= v[t] * g_.inv_degree[t];
            }
            y[a] = data + (smooth * lap + c * x[a]);
            xy += double(x[a]) * y[a];
          }
          return xy;
        },
        kBlock, 0.0);
  }

  double cost(const Eigen::VectorXf& d, const Linearisation& lin) {
    apply_rows<false>(nullptr, d, nullptr, scratch_lx_);
    double c = lin.data_cost + o_.weights.smooth * scratch_lx_.squaredNorm() + o_.weights.coarse * d.squaredNorm();
    // (Tested on the problem's vectors: with no free vertex the local ones are
    // empty, and the fixed share is then the whole term.)
    if (p_.prolonged.size()) c += o_.weights.hierarchy * ((d - prolonged_).squaredNorm() + prolonged_fixed_);
    if (p_.previous.size()) c += o_.weights.temporal * ((d - previous_).squaredNorm() + previous_fixed_);
    return c;
  }

  // Jacobi preconditioner: diag(J^T J).
  void diagonal(const Linearisation& lin, Eigen::VectorXf& diag) const {
    const int nf = g_.num_free;
    diag.resize(nf);
    const float smooth = float(o_.weights.smooth);
    for (int a = 0; a < nf; ++a) {
      float dd = lin.weight[a] * lin.self[a] * lin.self[a];
      float lap = g_.inv_degree[a] > 0 ? 1.0f : 0.0f;
      for (int k = g_.col_offsets[a]; k < g_.col_offsets[a + 1]; ++k) {
        const int t = g_.col_rows[k];
        const float j = lin.jac_by_column[k];
        dd += lin.weight[t] * j * j;
        lap += g_.inv_degree[t] * g_.inv_degree[t];
      }
      diag[a] = dd + smooth * lap + diag_const_;
    }
  }

  DisplacementReport run(Eigen::VectorXf& d_level) {
    DisplacementReport rep;
    const int nf = g_.num_free;
    Eigen::VectorXf d(nf);
    for (int a = 0; a < nf; ++a) d[a] = d_level[g_.global[a]];
    Linearisation lin;
    linearise(d, lin);
    double current = cost(d, lin);
    rep.initial_cost = current;
    Eigen::VectorXf grad, diag, lx, wgx, r, z, p, ap, x, trial;
    Linearisation trial_lin;
    for (rep.steps = 0; rep.steps < o_.gauss_newton_steps; ++rep.steps) {
      // Gradient J^T r of the whole energy.
      apply_rows<false>(nullptr, d, nullptr, lx);
      apply_columns(lin, lin.data_residual, lx, float(o_.weights.coarse), d, grad);
      if (prolonged_.size()) grad += float(o_.weights.hierarchy) * (d - prolonged_);
      if (previous_.size()) grad += float(o_.weights.temporal) * (d - previous_);
      diagonal(lin, diag);
      // Algorithm 2: PCG from x0 = 0 on (J^T J) x = -J^T r. One product
      // (J^T J) p is a row pass, then a column pass.
      x.setZero(nf);
      r = -grad;
      z = r.cwiseQuotient(diag);
      p = z;
      double rz = r.dot(z);
      for (int k = 0; k < o_.pcg_iterations && rz > 1e-30; ++k) {
        apply_rows<true>(&lin, p, &wgx, lx);
        const double pap = apply_columns(lin, wgx, lx, diag_const_, p, ap);
        if (pap <= 0) break;
        const float alpha = float(rz / pap);
        // x += alpha p, r -= alpha ap, z = M^-1 r and r . z in one pass.
        const double rz_new = parallel_sum(
            nf,
            [&](int b, int e) {
              double sum = 0;
              for (int a = b; a < e; ++a) {
                x[a] += alpha * p[a];
                r[a] -= alpha * ap[a];
                z[a] = r[a] / diag[a];
                sum += double(r[a]) * z[a];
              }
              return sum;
            },
            kBlock, 0.0);
        const float beta = float(rz_new / rz);
        parallel_for(
            nf,
            [&](int b, int e) {
              for (int a = b; a < e; ++a) p[a] = z[a] + beta * p[a];
            },
            kBlock);
        rz = rz_new;
      }
      // PCG from x0 = 0 keeps its residual -grad - H x orthogonal to x, so
      // x^T H x = -grad^T x and the quadratic model's decrease is
      // -grad^T x - x^T H x / 2 = -grad^T x / 2.
      const double predicted_decrease = -0.5 * double(grad.dot(x));
      if (predicted_decrease < o_.function_tolerance * current) {
        rep.converged = true;
        break;
      }
      // Gauss-Newton step; halved if it does not lower the energy.
      double trial_cost = current;
      float scale = 1.0f;
      for (int h = 0; h < 4; ++h, scale *= 0.5f) {
        trial = d + scale * x;
        linearise(trial, trial_lin);
        trial_cost = cost(trial, trial_lin);
        if (trial_cost < current) break;
      }
      if (!(trial_cost < current)) break;
      d.swap(trial);
      std::swap(lin, trial_lin);
      current = trial_cost;
    }
    rep.final_cost = current;
    d_level.setZero(lv_.num_vertices);
    for (int a = 0; a < nf; ++a) d_level[g_.global[a]] = d[a];
    return rep;
  }

 private:
  // Shading, its derivatives and the data residual of touched vertex t.
  void linearise_vertex(int t, Linearisation& lin) {
    const auto position = [&](int v) -> Vec3f { return positions_.col(v); };
    constexpr int kMaxRing = kMaxDisplacementRing;
    const int i = g_.global[t];
    const Vec3f pi = position(i);
    const Vec3f ni = p_.base_normals.col(i);
    // m = sum over corners (j, k) of a x b, a = p_j - p_i, b = p_k - p_i.
    // d/dd_i (a x b) = n_i x (a - b), d/dd_j = n_j x b, d/dd_k = a x n_k =
    // n_k x (-a): so dm/dd_i = n_i x sum (a - b), and a ring vertex's
    // dm/dd_s = n_s x u_s with u_s its corners' summed b (as j) and -a (as k).
    Vec3f m = Vec3f::Zero();
    Vec3f sum_a_minus_b = Vec3f::Zero();
    Vec3f u[kMaxRing];
    const int deg = std::min(lv_.rings.degree(i), kMaxRing);
    for (int s = 0; s < deg; ++s) u[s] = Vec3f::Zero();
    for (int c = lv_.corner_offsets[i]; c < lv_.corner_offsets[i + 1]; ++c) {
      const auto& [j, k] = lv_.corners[c];
      const auto& [sj, sk] = lv_.corner_slots[c];
      const Vec3f a = position(j) - pi, bvec = position(k) - pi;
      m += a.cross(bvec);
      sum_a_minus_b += a - bvec;
      if (sj >= 0 && sj < kMaxRing) u[sj] += bvec;
      if (sk >= 0 && sk < kMaxRing) u[sk] -= a;
    }
    const int rb = g_.row_offsets[t], re = g_.row_offsets[t + 1];
    const float len = m.norm();
    if (!(len > 0)) {
      lin.self[t] = 0;
      for (int e = rb; e < re; ++e) lin.jac[e] = 0;
      lin.weight[t] = 0;
      lin.data_residual[t] = 0;
      vertex_cost_[t] = 0;
      return;
    }
    const Vec3f nhat = m / len;
    const Vec3f v(nhat.x(), -nhat.y(), -nhat.z());  // viewer frame for SH
    const Vec3f gv = sh_gradient(p_.lighting, v);
    const Vec3f g(gv.x(), -gv.y(), -gv.z());  // back to the camera frame
    // ds/dm = g^T (I - n n^T) / |m|
    const Vec3f dsdm = (g - nhat * nhat.dot(g)) / len;
    // dsdm . (n x w) = w . (dsdm x n)
    lin.self[t] = sum_a_minus_b.dot(dsdm.cross(ni));
    for (int e = rb; e < re; ++e) {
      const int slot = g_.row_slots[e];
      lin.jac[e] = slot < kMaxRing ? u[slot].dot(dsdm.cross(Vec3f(p_.base_normals.col(g_.row_vertices[e])))) : 0.0f;
    }
    if (!p_.samples->visible[i]) {
      lin.weight[t] = 0;
      lin.data_residual[t] = 0;
      vertex_cost_[t] = 0;
      return;
    }
    const float s = float(sh_shade(p_.lighting, double(v.x()), double(v.y()), double(v.z())));
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
      vertex_cost_[t] = 2 * k * e - k * k;
    } else {
      vertex_cost_[t] = e2;
    }
    lin.weight[t] = robust * w;
    lin.data_residual[t] = robust * r;
  }

  const DisplacementProblem& p_;
  const DisplacementOptions o_;
  const MeshLevel& lv_;
  const DisplacementGraph g_;
  Positions positions_;  // the displaced surface on the whole level (the base where d is fixed)
  Eigen::VectorXf vertex_cost_;
  Eigen::VectorXf scratch_lx_;
  Eigen::VectorXf prolonged_, previous_;  // pd and d_prev at the free vertices
  double prolonged_fixed_ = 0, previous_fixed_ = 0;
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
  const auto t0 = std::chrono::steady_clock::now();
  Solver solver(problem, options);
  const double setup_ms = ms_since(t0);
  DisplacementReport report = solver.run(d);
  report.setup_ms = setup_ms;
  return report;
}

}  // namespace facecap
