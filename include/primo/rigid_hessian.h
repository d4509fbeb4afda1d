#pragma once
// The gradient and Hessian of a rigid system's energy in the motions (v, omega) of its bodies,
// as a matrix of 6x6 blocks (block_matrix.h): the Gauss-Newton blocks, plus the second-order
// rotation terms on the diagonal when asked (the exact Hessian in exponential coordinates, as
// global_solver.h uses). Inactive dofs of handles are masked: their rows and columns are zero
// with 1 on the diagonal, and their gradient entries are zero. Assembled in parallel, body by
// body and pair by pair: the same bits on any number of threads.

#include <utility>
#include <vector>

#include "primo/block_matrix.h"
#include "primo/rigid_system.h"

namespace primo {

class RigidHessian {
 public:
  explicit RigidHessian(const RigidSystem& system);

  // Gradient and matrix at `state`: the exact Hessian with `second_order`, else Gauss-Newton's.
  void assemble(const std::vector<BodyState>& state, bool second_order);

  const BlockMatrix& matrix() const { return matrix_; }
  const BlockVector& gradient() const { return gradient_; }
  // `state` moved by lambda * step: rotations through the exponential map, positions along v.
  std::vector<BodyState> moved(const std::vector<BodyState>& state, const BlockVector& step,
                               double lambda) const;

 private:
  const RigidSystem& system_;
  std::vector<int> mask_;                         // active_mask of each body
  Groups pair_couplings_;                         // each pair's couplings
  BlockMatrix matrix_;
  BlockVector gradient_;
};

}  // namespace primo
