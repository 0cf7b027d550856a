#include "facecap/refine/albedo.hpp"

#include "facecap/core/parallel.hpp"
#include "facecap/render/shading.hpp"

namespace facecap {

namespace {

// Vertices per block of the albedo PCG's parallel passes. The coarsest level
// has about 9.4k vertices, and each pass is a few tens of microseconds of
// work: in blocks of 1024, handing them out cost more than the second core
// gave (`refine_bench` BM_AlbedoPhase on this 2-core VM, alternating runs:
// 1402-1480 ms in blocks of 1024, 1069-1127 ms in blocks of 4096, 1240-1290 ms
// on one thread in a slower spell).
constexpr int kBlock = 4096;

// Per channel c, the sum over the vertices i of entry(i, c, q), q = 3 i + c
// (the entry's index in row-major n x 3 data); entry may also write there.
// Runs on the pool in fixed blocks (parallel_sum: independent of the thread
// count).
template <typename Entry>
Eigen::Array3d sum_over_entries(int n, const Entry& entry) {
  return parallel_sum(
      n,
      [&](int b, int e) {
        Eigen::Array3d sum = Eigen::Array3d::Zero();
        for (int i = b; i < e; ++i)
          for (int c = 0; c < 3; ++c) sum[c] += entry(i, c, 3 * i + c);
        return sum;
      },
      kBlock, Eigen::Array3d::Zero().eval());
}

}  // namespace

AlbedoEstimator::AlbedoEstimator(const MeshLevel& level, AlbedoOptions options)
    : level_(level),
      options_(options),
      data_diag_(Eigen::VectorXd::Zero(level.num_vertices)),
      data_rhs_(Eigen::Matrix3Xd::Zero(3, level.num_vertices)),
      albedo_(Positions::Constant(3, level.num_vertices, 0.5f)),
      inv_degree_(level.num_vertices) {
  for (int i = 0; i < level.num_vertices; ++i)
    inv_degree_[i] = level.rings.degree(i) > 0 ? 1.0 / level.rings.degree(i) : 0.0;
}

void AlbedoEstimator::initialise_uniform(const VertexSamples& samples) {
  Vec3f mean = Vec3f::Zero();
  int n = 0;
  for (Eigen::Index i = 0; i < samples.colour.cols(); ++i) {
    if (!samples.visible[i]) continue;
    mean += samples.colour.col(i);
    ++n;
  }
  if (n > 0) albedo_.colwise() = mean / float(n);
}

void AlbedoEstimator::clear_data() {
  data_diag_.setZero();
  data_rhs_.setZero();
  frames_ = 0;
}

void AlbedoEstimator::add_frame(const VertexSamples& samples, const Positions& normals, const ShCoeffs& lighting) {
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (!samples.visible[i]) continue;
    const Vec3f v = to_viewer_frame(Vec3f(normals.col(i)));
    const double s = sh_shade(lighting, double(v.x()), double(v.y()), double(v.z()));
    if (s <= 1e-3) continue;  // unlit: says nothing about the albedo
    data_diag_[i] += s * s;
    data_rhs_.col(i) += s * samples.colour.col(i).cast<double>();
  }
  ++frames_;
}

void AlbedoEstimator::laplacian_normal(const Channels& x, Channels& lx, Channels& out) const {
  // L = I - A / r (uniform graph Laplacian); out = L^T (L x). The second
  // product gathers over each ring (the rings are symmetric): entry i
  // collects lx_j / r_j from its neighbours j.
  const VertexAdjacency& r = level_.rings;
  const int n = level_.num_vertices;
  lx.resize(n, 3);
  out.resize(n, 3);
  parallel_for(
      n,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
          for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) sum += x.row(r.indices[s]);
          lx.row(i) =
              inv_degree_[i] > 0 ? Eigen::RowVector3d(x.row(i) - sum * inv_degree_[i]) : Eigen::RowVector3d::Zero();
        }
      },
      kBlock);
  parallel_for(
      n,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
          for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) {
            const int j = r.indices[s];
            sum += lx.row(j) * inv_degree_[j];
          }
          out.row(i) = lx.row(i) - sum;
        }
      },
      kBlock);
}

AlbedoEstimator::Channels AlbedoEstimator::solve_channels(const Eigen::VectorXd& d, const Channels& b, double w,
                                                          const Channels& prior, Channels x) const {
  const int n = level_.num_vertices;
  // Jacobi preconditioner: diag(D + w L^T L) = D_i + w (1 + sum_{j in ring(i)} 1/r_j^2).
  Eigen::VectorXd inv_diag(n);
  const VertexAdjacency& r = level_.rings;
  for (int i = 0; i < n; ++i) {
    double s = 1.0;
    for (int k = r.offsets[i]; k < r.offsets[i + 1]; ++k) s += inv_degree_[r.indices[k]] * inv_degree_[r.indices[k]];
    inv_diag[i] = 1.0 / (d[i] + w * s);
  }
  Channels lx, llx;
  // ap = (D + w L^T L) v, in place.
  const auto apply = [&](const Channels& v, Channels& ap) {
    laplacian_normal(v, lx, llx);
    ap = d.asDiagonal() * v;
    ap += w * llx;
  };
  laplacian_normal(prior, lx, llx);
  Channels res = b + w * llx;
  Channels ap;
  apply(x, ap);
  res -= ap;
  Channels z = inv_diag.asDiagonal() * res;
  Channels p = z;
  Eigen::Array3d rz = (res.array() * z.array()).colwise().sum().transpose();
  // Each iteration: the Laplacian passes, then two fused passes over the
  // vertices (ap and p.ap; x, res, z and res.z) and the update of p, all on
  // the pool. Raw row-major data: entry (i, c) at 3 i + c.
  double* const xd = x.data();
  double* const rd = res.data();
  double* const zd = z.data();
  double* const pd = p.data();
  double* const apd = ap.data();
  for (int k = 0; k < options_.pcg_iterations && (rz > 1e-20).any(); ++k) {
    laplacian_normal(p, lx, llx);
    const double* const lld = llx.data();
    const Eigen::Array3d pap = sum_over_entries(n, [&](int i, int, int q) {
      apd[q] = d[i] * pd[q] + w * lld[q];
      return pd[q] * apd[q];
    });
    // Converged columns hold still (alpha 0).
    const Eigen::Array3d alpha = (rz > 1e-20).select(rz / pap, 0.0);
    const Eigen::Array3d rz_new = sum_over_entries(n, [&](int i, int c, int q) {
      xd[q] += alpha[c] * pd[q];
      rd[q] -= alpha[c] * apd[q];
      zd[q] = inv_diag[i] * rd[q];
      return rd[q] * zd[q];
    });
    const Eigen::Array3d beta = (rz > 1e-20).select(rz_new / rz, 0.0);
    parallel_for(
        n,
        [&](int b, int e) {
          for (int i = b; i < e; ++i)
            for (int c = 0; c < 3; ++c)
              if (rz[c] > 1e-20) pd[3 * i + c] = zd[3 * i + c] + beta[c] * pd[3 * i + c];
        },
        kBlock);
    rz = (rz > 1e-20).select(rz_new, rz);
  }
  return x;
}

void AlbedoEstimator::solve() {
  const int n = level_.num_vertices;
  const Channels b = data_rhs_.transpose();
  const Channels start = albedo_.transpose().cast<double>();
  // The smooth prior rho_bar, then eq. 4.10 against it.
  const Channels prior = solve_channels(data_diag_, b, options_.prior_smoothing, Channels::Zero(n, 3), start);
  const Channels rho = solve_channels(data_diag_, b, options_.laplacian_weight, prior, prior);
  albedo_ = rho.cwiseMax(0.0).cwiseMin(2.0).transpose().cast<float>();
}

}  // namespace facecap
