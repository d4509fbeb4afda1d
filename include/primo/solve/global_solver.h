#pragma once
// Global shape matching (paper Sect. 4.2, Appendix A), after Pottmann et al. [PLH02]: every
// iteration linearizes all bodies' motions as (v, omega), solves the sparse normal equations
// of the joint and spring energy with CHOLMOD, maps the update back to rigid motions, and
// halves the step until the energy decreases.
//
// Two kinds of step:
//  - Gauss-Newton (the paper's): first-order motions x + omega x (x - c) + v, projected onto
//    the closest rigid motion measured on the body's own prism sides (Eq. 7).
//  - Exact Newton: the same system plus the second-order rotation terms of the true Hessian
//    in exponential coordinates, applied through the exponential map. Near the minimum it
//    converges quadratically where Gauss-Newton converges linearly. When that Hessian is not
//    positive definite the step falls back to Gauss-Newton.
//
// The sparsity pattern depends only on which bodies are coupled, so it is analysed once, when
// the solver is made, and every iteration only refactorizes numerically.

#include <memory>
#include <vector>

#include "primo/model/rigid_system.h"

namespace primo {

struct GlobalStep {
  double energy_before = 0.0;
  double energy_after = 0.0;
  double step_scale = 0.0;  // lambda that was accepted (0 when no step lowered the energy)
  bool exact_hessian = false;
  bool decreased = false;
  bool reused_factorization = false;  // the step came from an earlier iteration's factor
};

// Accumulated wall time per phase since the solver was made (or timings were reset).
struct GlobalSolverTimings {
  double assembly = 0.0;
  double factorization = 0.0;
  double solve = 0.0;
  double line_search = 0.0;  // rigid updates and energy evaluations
  int factorizations = 0;
  int failed_factorizations = 0;  // not positive definite
  double background_factorization = 0.0;  // on the background thread (not in the wall time)
  int background_factorizations = 0;
  int energy_evaluations = 0;
};

class GlobalSolver {
 public:
  enum class Factorization {
    // Simplicial below kSupernodalFromDofs unknowns, supernodal above. Small systems (the
    // coarse level of the hierarchy) factorize as fast without dense blocks, and without
    // waking BLAS threads, which on two shared cores costs more than it saves.
    Automatic,
    Supernodal,  // dense supernodes through BLAS (OpenBLAS: threaded)
    // Supernodal with OpenBLAS held to the calling thread: for solves between our own
    // two-thread sweeps, which idle BLAS threads would otherwise slow down.
    SupernodalOneThread,
    Simplicial,  // up-looking, no BLAS
  };
  static constexpr int kSupernodalFromDofs = 6000;

  explicit GlobalSolver(const RigidSystem& system,
                        Factorization factorization = Factorization::Automatic);
  ~GlobalSolver();
  GlobalSolver(const GlobalSolver&) = delete;
  GlobalSolver& operator=(const GlobalSolver&) = delete;

  // One iteration from `state` (updated in place when the energy decreased). With
  // `exact_hessian` the second-order rotation terms are added when they keep the system
  // positive definite. With `reuse_factorization` the factor of the previous iteration is
  // tried first (a modified Newton step, for systems whose matrix changes slowly between
  // calls); a fresh one is made when it has none or its step does not lower the energy.
  GlobalStep iterate(std::vector<BodyState>& state, bool exact_hessian,
                     bool reuse_factorization = false);
  // A Gauss-Newton factor of `state` for the next reusing iterations, without a step (a
  // caller that knows where the next iterations start can make it ahead of time). Returns
  // whether the factorization succeeded.
  bool factorize_at(const std::vector<BodyState>& state);
  // How a reusing caller's factors are refreshed: a factor serves its first step and at most
  // `max_reuse` more (default: no limit), then the next step makes a fresh one. With
  // `background_lag` > 0 (supernodal factorizations only) the fresh one is made on a background
  // thread from the matrix of the step that found the factor spent, while steps go on with the
  // old factor; it takes over `background_lag` steps later, waiting for the thread if needed. A
  // step that fails with the old factor takes the new one at once. The takeover step is fixed,
  // so the iterates do not depend on timing. A reused factor's step may be halved up to
  // `reused_step_halvings` times before it counts as failed (and a fresh factor is made).
  void set_factor_reuse(int max_reuse, int background_lag = 0,
                        int reused_step_halvings = kReusedStepHalvings);
  static constexpr int kReusedStepHalvings = 3;
  // Frames (a rotation per body, owned by the caller and kept current) in which the bodies'
  // motions are measured, e.g. the orientation of a coarse cluster's prisms. A reused factor
  // is then applied turned by each body's rotation since its matrix was assembled: a pose
  // that turned as a whole keeps an exact Newton step.
  void set_body_frames(const std::vector<Mat3>* frames);

  int n_dofs() const;
  // Floating-point operations of the last foreground supernodal factorization (0 before one).
  double factorization_flops() const;
  // Whether a factor is there to reuse (the next reusing step need not factorize).
  bool has_factor() const;
  const GlobalSolverTimings& timings() const;
  void reset_timings();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// exp([w]x) by Rodrigues' formula.
Mat3 rotation_from_vector(const Vec3& w);

}  // namespace primo
