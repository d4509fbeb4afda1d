#pragma once
// A multigrid preconditioner for the Hessian of the energy in the bodies' motions (the linear
// systems of Newton-Krylov steps, newton_krylov.h), built on the same rigid clusters as the
// hierarchical solver: a cluster's motion (v, omega) moves each of its bodies rigidly,
// v_i = v + omega x (x_i - x_cluster), so the coarse matrices are Galerkin projections
// P^T A P of the fine one. One application is a V-cycle from zero: symmetric block
// Gauss-Seidel sweeps (forward before the coarse correction, backward after, over the parts
// and colours of body_partition.h) and a sparse Cholesky factor (CHOLMOD) on the coarsest
// level. It is symmetric and positive definite when the matrix is, so conjugate gradients can
// use it; and it gives the same bits on any number of threads.
//
// Why not the nonlinear cycles themselves: they converge at a fixed rate (about 0.95 of the
// error per cycle on the 100k koala), where conjugate gradients on the linear problem,
// preconditioned by this cycle, reduce it by about 0.5 per application (docs/performance.md).

#include <memory>
#include <utility>
#include <vector>

#include "primo/solve/block_matrix.h"
#include "primo/solve/body_partition.h"
#include "primo/model/rigid_system.h"

namespace primo {

// Defaults measured on the 29k armadillo and a 240k-face mesh (docs/performance.md,
// "Newton-Krylov"): clusters of 4 with the K-cycle took 5-8 iterations of conjugate gradients
// per Newton step where clusters of 8 took 11-20 (V- or K-cycle) at 240k, for about 1.7 times
// the cost per iteration.
struct MultigridOptions {
  int cluster_size = 4;           // bodies per cluster on every level
  int coarsest_max_bodies = 600;  // coarsen until at most this many clusters
  int smoothing_sweeps = 1;       // Gauss-Seidel sweeps before and after each coarse correction
  // 1: V-cycle (a fixed linear map, symmetric); 2: K-cycle, every coarse correction but the
  // coarsest two steps of flexible conjugate gradients (a slightly nonlinear map: the outer
  // conjugate gradients then read their beta as Polak-Ribiere's would, see newton_krylov.cpp).
  int coarse_visits = 2;
};

// The smoothing partition of the cycle's finest sweeps (by rest positions and coupled pairs),
// and the rows it numbers: the bodies of `fine` part after part, each part in index order, so
// that every part's rows are contiguous. A fine matrix whose rows are in this order
// (rigid_hessian.h) lets those sweeps stream each part's blocks: at 192,000 bodies a cycle
// took 105 ms in body order (`primo_microbench --benchmark_filter=MultigridCycle`).
struct MultigridRows {
  std::vector<int> order;  // the body of each row
  // Of the rows: what partitioning them again would give (the same parts, as runs of rows).
  BodyPartition partition;
};
MultigridRows multigrid_rows(const RigidSystem& fine);

class RigidMultigrid {
 public:
  // Levels for the bodies of `fine` (handles stay alone in their clusters) and fine matrices
  // whose off-diagonal blocks are `fine_pairs`, with row r for body fine_order[r] (empty: row b
  // for body b; rigid_hessian.h). `fine_partition` is the fine level's smoothing partition
  // of those rows (multigrid_rows' for its order), made here when empty. Coarse levels number
  // their clusters part after part of their smoothing partitions: a sweep then streams each
  // part's rows.
  RigidMultigrid(const RigidSystem& fine, const std::vector<std::pair<int, int>>& fine_pairs,
                 const MultigridOptions& options = {}, const std::vector<int>& fine_order = {},
                 BodyPartition fine_partition = {});
  ~RigidMultigrid();
  RigidMultigrid(const RigidMultigrid&) = delete;
  RigidMultigrid& operator=(const RigidMultigrid&) = delete;

  // Takes the fine matrix (kept by reference until the next call) at the bodies' current
  // positions (by row), projects it onto every level and factorizes. False when a diagonal block or
  // the coarsest matrix is not positive definite (the cycle is then not to be used).
  bool set_matrix(const BlockMatrix& fine, const std::vector<Vec3>& position);
  // z = M^-1 r: one cycle, in single precision: a preconditioner needs a few digits, and with
  // half the bytes and no conversions a cycle at 192,000 bodies took 54 instead of 64 ms
  // (medians of 8 alternating runs), with the same iterations at 240k faces.
  void apply(const BlockVector& r, BlockVector& z);

  int levels() const;  // including the fine level
  int bodies(int level) const;

 private:
  struct Level;
  struct Coarsest;
  void cycle(size_t l, const BlockVectorF& rhs, BlockVectorF& x);
  void krylov_correction(size_t l);  // level l's `x` from its `rhs`
  // FromZero: a forward sweep of an x that is zero (a cycle's first), reading only the rows
  // swept before each row.
  enum class Sweep { FromZero, Forward, Backward };
  void sweep(const Level& level, const BlockVectorF& rhs, BlockVectorF& x, Sweep direction) const;

  MultigridOptions options_;
  std::vector<std::unique_ptr<Level>> levels_;  // fine first
  std::unique_ptr<Coarsest> coarsest_;
};

}  // namespace primo
