#include "facecap/fit/identity_solver.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "facecap/core/parallel.hpp"

namespace facecap {

namespace {

// One frame's linearisation restricted to its free variables.
struct FrameSystem {
  std::vector<int> free;  // indices into the frame block
  Eigen::MatrixXd a;      // J_F^T J_F
  Eigen::MatrixXd b;      // J_F^T K
  Eigen::VectorXd g;      // J_F^T r (+ l1 on weights)
  Eigen::MatrixXd ktk;    // K^T K
  Eigen::VectorXd ktr;    // K^T r
  double cost = 0;
};

double shared_prior_cost(const Eigen::VectorXd& identity, double focal, const IdentitySolverOptions& o) {
  double c = 0.5 * identity.squaredNorm();  // a ~ N(0, 1)
  const double rf = (std::log(focal) - std::log(o.focal_guess)) / o.sigma_log_focal;
  return c + 0.5 * rf * rf;
}

double total_cost(const std::vector<std::unique_ptr<FrameEnergy>>& energies, const std::vector<FrameParameters>& frames,
                  const Eigen::VectorXd& identity, double focal, const IdentitySolverOptions& o) {
  const int n = static_cast<int>(frames.size());
  std::vector<double> costs(n, 0.0);
  parallel_for(
      n,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          energies[i]->set_shared(identity, focal);
          costs[i] = energies[i]->cost(frames[i]);
        }
      },
      1);
  double total = shared_prior_cost(identity, focal, o);
  for (double c : costs) total += c;
  return total;
}

// Posterior covariance of the identity from one linearisation (Gauss-Newton,
// no damping): every frame's own unknowns and the focal length eliminated
// from the precision (Schur complements, i.e. marginalised), the N(0, 1)
// prior included, then inverted. Empty when the precision is singular.
Eigen::MatrixXd identity_posterior_covariance(const std::vector<FrameSystem>& sys,
                                              const Eigen::MatrixXd& shared_precision, int ni) {
  Eigen::MatrixXd p = shared_precision;
  for (const FrameSystem& s : sys) {
    Eigen::MatrixXd a = s.a;
    a.diagonal() += 1e-9 * a.diagonal().cwiseMax(1.0);  // unexcited weights: no information, not a singular solve
    p.noalias() -= s.b.transpose() * a.ldlt().solve(s.b);
  }
  if (p.rows() > ni) {  // the focal length
    const double pff = p(ni, ni);
    if (pff > 0) p.topLeftCorner(ni, ni).noalias() -= p.topRightCorner(ni, 1) * p.bottomLeftCorner(1, ni) / pff;
  }
  const Eigen::LDLT<Eigen::MatrixXd> f(p.topLeftCorner(ni, ni));
  if (f.info() != Eigen::Success) return {};
  return f.solve(Eigen::MatrixXd::Identity(ni, ni));
}

// Fills the report's posterior from the last linearisation. The prior's
// precision is 1 per mode, so ni - trace(covariance) counts the directions
// the landmarks determine, each by its data precision over its total.
void record_posterior(const std::vector<FrameSystem>& sys, const Eigen::MatrixXd& shared_precision, int ni,
                      IdentitySolveReport& rep) {
  rep.identity_covariance = identity_posterior_covariance(sys, shared_precision, ni);
  rep.effective_modes =
      rep.identity_covariance.size() ? std::clamp(ni - rep.identity_covariance.trace(), 0.0, double(ni)) : 0.0;
}

}  // namespace

IdentitySolveReport solve_identity_joint(const std::vector<std::unique_ptr<FrameEnergy>>& energies,
                                         std::vector<FrameParameters>& frames, Eigen::VectorXd& identity, double& focal,
                                         const IdentitySolverOptions& o) {
  IdentitySolveReport rep;
  const int n = static_cast<int>(frames.size());
  const int ni = static_cast<int>(identity.size());
  const int ny = ni + (o.focal_free ? 1 : 0);
  const int block = frames.empty() ? 0 : static_cast<int>(frames[0].values.size());
  const int first_weight = frame_block::kExpression;
  double lambda = 1e-3;
  if (o.refresh) o.refresh(frames, identity, focal);
  double cost = total_cost(energies, frames, identity, focal, o);
  rep.initial_cost = cost;
  std::vector<FrameSystem> sys(n);

  for (rep.iterations = 0; rep.iterations < o.max_iterations; ++rep.iterations) {
    if (o.refresh && rep.iterations > 0 && rep.iterations % o.refresh_every == 0) {
      o.refresh(frames, identity, focal);
      cost = total_cost(energies, frames, identity, focal, o);
    }
    // Linearise every frame (in parallel).
    parallel_for(
        n,
        [&](int b, int e) {
          Eigen::VectorXd r;
          Eigen::MatrixXd j, k;
          for (int i = b; i < e; ++i) {
            FrameSystem& s = sys[i];
            energies[i]->set_shared(identity, focal);
            s.cost = energies[i]->linearize(frames[i], r, j, &k);
            if (!o.focal_free) k.conservativeResize(Eigen::NoChange, ni);
            Eigen::VectorXd grad = j.transpose() * r;
            grad.tail(block - first_weight).array() += energies[i]->expression_l1();
            // Active set: weights at a bound that the gradient pushes outward stay put.
            s.free.clear();
            for (int c = 0; c < block; ++c) {
              if (c >= first_weight) {
                const double w = frames[i].values[c];
                if ((w <= 1e-12 && grad[c] > 0) || (w >= 1.0 - 1e-12 && grad[c] < 0)) continue;
              }
              s.free.push_back(c);
            }
            const int nf = static_cast<int>(s.free.size());
            Eigen::MatrixXd jf(j.rows(), nf);
            s.g.resize(nf);
            for (int c = 0; c < nf; ++c) {
              jf.col(c) = j.col(s.free[c]);
              s.g[c] = grad[s.free[c]];
            }
            s.a.noalias() = jf.transpose() * jf;
            s.b.noalias() = jf.transpose() * k;
            s.ktk.noalias() = k.transpose() * k;
            s.ktr.noalias() = k.transpose() * r;
          }
        },
        1);
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(ny, ny);
    Eigen::VectorXd gy = Eigen::VectorXd::Zero(ny);
    for (const FrameSystem& s : sys) {
      u += s.ktk;
      gy += s.ktr;
    }
    u.topLeftCorner(ni, ni).diagonal().array() += 1.0;  // identity prior
    gy.head(ni) += identity;
    if (o.focal_free) {
      const double jf = 1.0 / (focal * o.sigma_log_focal);
      const double rf = (std::log(focal) - std::log(o.focal_guess)) / o.sigma_log_focal;
      u(ni, ni) += jf * jf;
      gy[ni] += jf * rf;
    }

    bool accepted = false;
    for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
      // Schur complement on the shared unknowns.
      Eigen::MatrixXd schur = u;
      schur.diagonal() += lambda * u.diagonal().cwiseMax(1e-9);
      Eigen::VectorXd rhs = gy;
      // Each frame's elimination on its own (in parallel), its terms then
      // subtracted in frame order, so the sums do not depend on the threads.
      std::vector<Eigen::MatrixXd> ainv_b(n), schur_terms(n);
      std::vector<Eigen::VectorXd> ainv_g(n), rhs_terms(n);
      parallel_for(
          n,
          [&](int b, int e) {
            for (int i = b; i < e; ++i) {
              Eigen::MatrixXd a = sys[i].a;
              a.diagonal() += lambda * sys[i].a.diagonal().cwiseMax(1e-9);
              const Eigen::LDLT<Eigen::MatrixXd> factor(a);
              ainv_b[i] = factor.solve(sys[i].b);
              ainv_g[i] = factor.solve(sys[i].g);
              schur_terms[i].noalias() = sys[i].b.transpose() * ainv_b[i];
              rhs_terms[i].noalias() = sys[i].b.transpose() * ainv_g[i];
            }
          },
          1);
      for (int i = 0; i < n; ++i) {
        schur -= schur_terms[i];
        rhs -= rhs_terms[i];
      }
      if (!o.identity_free) {
        // Held: the identity rows decouple and their step is zero; what is
        // left of the Schur complement is the focal length's, given the identity.
        schur.topRows(ni).setZero();
        schur.leftCols(ni).setZero();
        schur.topLeftCorner(ni, ni).setIdentity();
        rhs.head(ni).setZero();
      }
      const Eigen::VectorXd dy = -schur.ldlt().solve(rhs);
      std::vector<FrameParameters> trial = frames;
      for (int i = 0; i < n; ++i) {
        const Eigen::VectorXd dx = -(ainv_g[i] + ainv_b[i] * dy);
        for (size_t c = 0; c < sys[i].free.size(); ++c) {
          const int col = sys[i].free[c];
          double v = trial[i].values[col] + dx[static_cast<Eigen::Index>(c)];
          if (col >= first_weight) v = std::clamp(v, 0.0, 1.0);  // projection onto the box
          trial[i].values[col] = v;
        }
      }
      const Eigen::VectorXd trial_identity = identity + dy.head(ni);
      const double trial_focal = o.focal_free ? std::max(0.2 * o.focal_guess, focal + dy[ni]) : focal;
      const double trial_cost = total_cost(energies, trial, trial_identity, trial_focal, o);
      if (trial_cost < cost) {
        accepted = true;
        const double decrease = cost - trial_cost;
        frames = std::move(trial);
        identity = trial_identity;
        focal = trial_focal;
        cost = trial_cost;
        lambda = std::max(1e-8, lambda / 3.0);
        if (decrease < 1e-7 * (1.0 + cost)) {
          ++rep.iterations;
          rep.final_cost = cost;
          record_posterior(sys, u, ni, rep);
          return rep;
        }
      } else {
        lambda *= 4.0;
      }
    }
    if (!accepted || rep.iterations + 1 == o.max_iterations) record_posterior(sys, u, ni, rep);
    if (!accepted) break;
  }
  rep.final_cost = cost;
  return rep;
}

}  // namespace facecap
