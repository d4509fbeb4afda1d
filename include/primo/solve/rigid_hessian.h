#pragma once
// The gradient and Hessian of a rigid system's energy in the motions (v, omega) of its bodies,
// as a matrix of 6x6 blocks (block_matrix.h): the Gauss-Newton blocks, plus the second-order
// rotation terms on the diagonal when asked (the exact Hessian in exponential coordinates, as
// global_solver.h uses). Inactive dofs of handles are masked: their rows and columns are zero
// with 1 on the diagonal, and their gradient entries are zero. Assembled in parallel row by
// row (each pair's block by its first row): the same bits on any number of threads.
//
// Rows can be numbered in another order than the bodies (`order`): the multigrid
// preconditioner's sweeps go part by part (rigid_multigrid.h), and with each part's rows
// contiguous they stream the blocks instead of fetching each row from afar (a product with
// this matrix is bound by memory traffic; at 192,000 bodies a cycle took 105 ms in body order).

#include <utility>
#include <vector>

#include "primo/solve/block_matrix.h"
#include "primo/model/rigid_system.h"

namespace primo {

class RigidHessian {
 public:
  // Row r is body order[r] (every body once); empty: row b is body b.
  explicit RigidHessian(const RigidSystem& system, std::vector<int> order = {});

  // Gradient and matrix at `state`: the exact Hessian with `second_order`, else Gauss-Newton's.
  void assemble(const std::vector<BodyState>& state, bool second_order);

  const BlockMatrix& matrix() const { return matrix_; }
  const BlockVector& gradient() const { return gradient_; }
  const std::vector<int>& order() const { return order_; }  // the body of each row
  // `state` (by body) moved by lambda * step (by row) into `out` (resized to fit): rotations
  // through the exponential map, positions along v. A line search that keeps `out` between
  // steps writes into memory it has, where a fresh vector (23 MB at 240k faces) is fresh
  // pages to fault in.
  void move_into(const std::vector<BodyState>& state, const BlockVector& step, double lambda,
                 std::vector<BodyState>& out) const;

 private:
  // What a row reads of a coupling (128 bytes, where RigidSystem::Coupling has 280 with the
  // modes that only local matching and the energy need), numbered in the order the rows
  // first meet them: rows stream their couplings instead of fetching them from afar. With
  // RowConstants, the assembly at 192,000 bodies took 39-49 ms (least and median of 15 runs)
  // against 49-63 ms, for 61 MB more while a solve's steps keep their structure at 240k faces.
  struct CouplingTerms {
    CouplingTerms() {}  // uninitialized: written in parallel, which places their pages
    Mat3 cross;         // RigidSystem::Coupling::cross (side 0's; side 1 reads its transpose)
    Vec3 mean[2];       // each side's point mode in its body's frame
    double weight;
  };
  // A row's couplings (CSR by row): their terms, the other body, the side the row is on,
  // and the pair whose block the row writes (-1: none, or the other row writes it).
  struct RowCoupling {
    int terms;
    int other;
    int side;
    int pair;
  };
  // The parts of a row's blocks that do not depend on the state: sums over its couplings of
  // w, of w l (the point mode) and of w l l^T over all modes l, in its body's frame (they
  // are turned into the world once per assembly).
  struct RowConstants {
    double weight = 0.0;
    Vec3 arm = Vec3::Zero();
    Mat3 yy = Mat3::Zero();
  };

  const RigidSystem& system_;
  std::vector<int> order_;   // row -> body
  std::vector<int> row_of_;  // body -> row
  std::vector<int> mask_;    // active_mask of each row's body
  std::vector<CouplingTerms> terms_;
  std::vector<int> row_coupling_begin_;
  std::vector<RowCoupling> row_couplings_;
  std::vector<RowConstants> row_constants_;
  BlockMatrix matrix_;
  BlockVector gradient_;
};

}  // namespace primo
