#include "facecap/refine/albedo_solver.hpp"

#include <array>

#include "facecap/core/parallel.hpp"

#if FACECAP_HAVE_CUDA
#include "facecap/refine/cuda/cuda_albedo_solver.hpp"
#endif

namespace facecap {

AlbedoLaplacian::AlbedoLaplacian(const MeshLevel& level)
    : rings(&level.rings), inv_degree(level.num_vertices), normal_diagonal(level.num_vertices) {
  const VertexAdjacency& r = level.rings;
  for (int i = 0; i < level.num_vertices; ++i) inv_degree[i] = r.degree(i) > 0 ? 1.0 / r.degree(i) : 0.0;
  for (int i = 0; i < level.num_vertices; ++i) {
    double s = 1.0;
    for (int k = r.offsets[i]; k < r.offsets[i + 1]; ++k) s += inv_degree[r.indices[k]] * inv_degree[r.indices[k]];
    normal_diagonal[i] = s;
  }
}

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

class CpuAlbedoSolver final : public AlbedoSolver {
 public:
  explicit CpuAlbedoSolver(const MeshLevel& level) : laplacian_(level) {}

  AlbedoChannels solve(const Eigen::VectorXd& d, const AlbedoChannels& b, double w, const AlbedoChannels& prior,
                       AlbedoChannels x, int iterations) override;

 private:
  // out = L^T L x, per column (lx: scratch for L x).
  void laplacian_normal(const AlbedoChannels& x, AlbedoChannels& lx, AlbedoChannels& out) const;

  AlbedoLaplacian laplacian_;
};

void CpuAlbedoSolver::laplacian_normal(const AlbedoChannels& x, AlbedoChannels& lx, AlbedoChannels& out) const {
  // L = I - A / r (uniform graph Laplacian); out = L^T (L x). The second
  // product gathers over each ring (the rings are symmetric): entry i
  // collects lx_j / r_j from its neighbours j.
  const VertexAdjacency& r = *laplacian_.rings;
  const Eigen::VectorXd& inv_degree = laplacian_.inv_degree;
  const int n = laplacian_.num_vertices();
  lx.resize(n, 3);
  out.resize(n, 3);
  parallel_for(
      n,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
          for (int s = r.offsets[i]; s < r.offsets[i + 1]; ++s) sum += x.row(r.indices[s]);
          lx.row(i) =
              inv_degree[i] > 0 ? Eigen::RowVector3d(x.row(i) - sum * inv_degree[i]) : Eigen::RowVector3d::Zero();
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
            sum += lx.row(j) * inv_degree[j];
          }
          out.row(i) = lx.row(i) - sum;
        }
      },
      kBlock);
}

AlbedoChannels CpuAlbedoSolver::solve(const Eigen::VectorXd& d, const AlbedoChannels& b, double w,
                                      const AlbedoChannels& prior, AlbedoChannels x, int iterations) {
  const int n = laplacian_.num_vertices();
  // Jacobi preconditioner: diag(D + w L^T L) = D_i + w (1 + sum_{j in ring(i)} 1/r_j^2).
  const Eigen::VectorXd inv_diag = (d + w * laplacian_.normal_diagonal).cwiseInverse();
  AlbedoChannels lx, llx;
  // ap = (D + w L^T L) v, in place.
  const auto apply = [&](const AlbedoChannels& v, AlbedoChannels& ap) {
    laplacian_normal(v, lx, llx);
    ap = d.asDiagonal() * v;
    ap += w * llx;
  };
  laplacian_normal(prior, lx, llx);
  AlbedoChannels res = b + w * llx;
  AlbedoChannels ap;
  apply(x, ap);
  res -= ap;
  AlbedoChannels z = inv_diag.asDiagonal() * res;
  AlbedoChannels p = z;
  Eigen::Array3d rz = (res.array() * z.array()).colwise().sum().transpose();
  // Each iteration: the Laplacian passes, then two fused passes over the
  // vertices (ap and p.ap; x, res, z and res.z) and the update of p, all on
  // the pool. Raw row-major data: entry (i, c) at 3 i + c.
  double* const xd = x.data();
  double* const rd = res.data();
  double* const zd = z.data();
  double* const pd = p.data();
  double* const apd = ap.data();
  for (int k = 0; k < iterations && (rz > 1e-20).any(); ++k) {
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
    // Local copies: pd's stores could alias rz and beta, which the compiler
    // would then read again for every entry.
    const std::array<double, 3> step = {beta[0], beta[1], beta[2]};
    const std::array<bool, 3> moving = {rz[0] > 1e-20, rz[1] > 1e-20, rz[2] > 1e-20};
    parallel_for(
        n,
        [&, step, moving](int b, int e) {
          for (int i = b; i < e; ++i)
            for (int c = 0; c < 3; ++c)
              if (moving[c]) pd[3 * i + c] = zd[3 * i + c] + step[c] * pd[3 * i + c];
        },
        kBlock);
    rz = (rz > 1e-20).select(rz_new, rz);
  }
  return x;
}

}  // namespace

std::unique_ptr<AlbedoSolver> make_albedo_solver(ComputeDevice device, const MeshLevel& level) {
  if (device == ComputeDevice::cpu) return std::make_unique<CpuAlbedoSolver>(level);
  require_cuda();
#if FACECAP_HAVE_CUDA
  return std::make_unique<CudaAlbedoSolver>(level);
#else
  return nullptr;  // not reached: require_cuda throws in a build without CUDA
#endif
}

}  // namespace facecap
