#pragma once
// Newton steps on all bodies at once, each solved inexactly by conjugate gradients
// preconditioned by the rigid-cluster multigrid cycle (rigid_multigrid.h): a solve from afar
// (HierarchicalOptions::newton_krylov_above) and, as an option, the tail of a settle. The
// hierarchical cycles remove a fixed fraction of the error per cycle (a few percent at 240k
// faces), where Newton steps converge quadratically near a minimum; a direct
// factorization of the fine Newton system, which global matching uses, costs seconds and
// gigabytes at that size, and conjugate gradients need only products with the Hessian's
// blocks and a cheap cycle.
//
// A step: the exact Hessian (the Gauss-Newton blocks plus the second-order rotation terms,
// as global_solver.h) and gradient in the motions (v, omega) of every body; conjugate
// gradients until an iteration adds little to the quadratic model's decrease; the update through the
// exponential map, halved until the energy drops. Where the Hessian or its diagonal blocks
// are not positive definite (away from a minimum) the Gauss-Newton matrix is used instead.
// The same bits on any number of threads.

#include <functional>
#include <memory>
#include <vector>

#include "primo/solve/rigid_multigrid.h"
#include "primo/model/rigid_system.h"

namespace primo {

struct NewtonKrylovOptions {
  MultigridOptions multigrid;
  // Conjugate gradients stop after an iteration that lowered the step's quadratic model by at
  // most this fraction of what all its iterations lowered it (each iteration's decrease is
  // alpha r.z / 2, known without another preconditioner application; Arioli's estimate of
  // the error in the energy norm), or after `max_cg_iterations`. A test on the preconditioned
  // residual r.z, as before, applied the preconditioner once more per step only to decide
  // to stop: 47 applications for 39 iterations in the 240k full solve, 34 for 34 with this
  // test at 0.1, the same steps (docs/decisions/0005-newton-krylov-steps-for-the-tail.md).
  double stop_ratio = 0.1;
  int max_cg_iterations = 40;
  // The largest turn (radians) a body may make in one step: conjugate gradients stop where
  // their iterate would turn a body further, on that bound (Steihaug's truncated conjugate
  // gradients, the trust region measured by the largest turn; 0: no bound). Away from the
  // minimum the exact Hessian can be nearly singular in a direction that the first iterations
  // have not reached yet; the later ones then turn whole regions by radians (6 to 30 on the
  // koala's full solve), and halving such a step leaves little of the good part of it. The
  // bound keeps the early iterations' step instead (docs/decisions/0006).
  double max_turn = 0.3;
  int max_halvings = 12;
};

struct NewtonKrylovStep {
  double energy_before = 0.0;
  double energy_after = 0.0;
  double step_scale = 0.0;  // accepted fraction of the step (0: none lowered the energy)
  int cg_iterations = 0;
  int preconditioner_applications = 0;
  // The quadratic model's decrease by each conjugate-gradient iteration of the accepted
  // solve, in order (alpha r.z / 2, in the units of E / 2).
  std::vector<double> model_decreases;
  double largest_turn = 0.0;  // of any body in the full step (before step halving), radians
  bool turn_bounded = false;  // conjugate gradients stopped on NewtonKrylovOptions::max_turn
  bool exact_hessian = false;
  bool decreased = false;
  bool interrupted = false;  // `interrupt` said so before the step was found: state unchanged
};

class NewtonKrylov {
 public:
  NewtonKrylov(const RigidSystem& system, const NewtonKrylovOptions& options = {});
  ~NewtonKrylov();
  NewtonKrylov(const NewtonKrylov&) = delete;
  NewtonKrylov& operator=(const NewtonKrylov&) = delete;

  // One step from `state` (updated in place when the energy decreased); `energy_before` is the
  // energy of `state` (computed when NaN). `interrupt`, when given, is asked before the step,
  // between the parts of the first step's structure (the row order, the Hessian's pattern,
  // the multigrid's levels) and before each conjugate-gradient iteration; true abandons the
  // step (the parts of the structure built so far are kept for the next).
  NewtonKrylovStep iterate(std::vector<BodyState>& state, double energy_before,
                           const std::function<bool()>& interrupt = {});
  // Builds the steps' structure now (what the first step would build), without asking
  // anyone: the hierarchical solver builds it beside a coarse factorization that leaves a
  // core idle (HierarchicalSolver::set_iterations_ahead).
  void build_structure();
  bool structure_built() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace primo
