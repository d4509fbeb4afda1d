#pragma once
// Where the time of a drag goes (`primo bench drag`, docs/performance.md): the solvers' phase
// timers read before and after a stretch of work, and the differences as one table row.

#include <nlohmann/json.hpp>

#include "primo/solve/deformer.h"
#include "primo/solve/global_solver.h"

namespace primo::bench {

// The solvers' accumulated phase timings at one moment; differences give a phase's share.
struct SolverClock {
  double restrict_prolong = 0.0;
  double coarse = 0.0;
  double sweeps = 0.0;
  double acceleration = 0.0;
  double newton_krylov = 0.0;
  int newton_krylov_steps = 0;
  int newton_krylov_iterations = 0;
  int newton_krylov_applications = 0;
  int cycles = 0;
  GlobalSolverTimings newton;  // the coarse level's solver (hierarchical) or the global solver

  static SolverClock read(const Deformer& deformer);
};

// Where the wall time of a phase went, in seconds. `other` is what no solver timer covers:
// energy evaluations in Deformer::solve and after each cycle, local sweeps of the Local
// method, building the hierarchy or the global solver's analysis on first use.
struct Breakdown {
  double total = 0.0;
  double set_targets = 0.0;
  double restrict_prolong = 0.0;
  double coarse = 0.0;
  double assembly = 0.0;
  double factorization = 0.0;
  double solve = 0.0;
  double line_search = 0.0;
  double sweeps = 0.0;
  double acceleration = 0.0;  // Anderson proposals and their energy
  double newton_krylov = 0.0;        // Newton-Krylov steps, all their phases
  double newton_krylov_steps = 0.0;  // count
  double newton_krylov_iterations = 0.0;  // count of their conjugate-gradient iterations
  double newton_krylov_applications = 0.0;  // count of their preconditioner's applications
  double vertex_update = 0.0;
  double factorizations = 0.0;  // count (per frame after per())

  double newton() const { return assembly + factorization + solve + line_search; }
  double other() const;
  // Adds what the solvers' timers say happened between `before` and `after`.
  void add_solver(const SolverClock& before, const SolverClock& after);
  // Every figure divided by `n` (frames).
  Breakdown per(int n) const;
  nlohmann::json to_json_ms() const;
};

// One row of the "Where the time goes" table, in ms; `coarse` only for the hierarchical method.
void print_breakdown_row(const char* label, const Breakdown& b, SolveMethod method);

}  // namespace primo::bench
