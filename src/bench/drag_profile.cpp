#include "drag_profile.h"

#include <algorithm>
#include <cstdio>

#include "primo/solve/hierarchical_solver.h"

namespace primo::bench {

SolverClock SolverClock::read(const Deformer& deformer) {
  SolverClock c;
  if (const HierarchicalSolver* h = deformer.hierarchical_solver()) {
    c.restrict_prolong = h->timings().restrict_prolong;
    c.coarse = h->timings().coarse;
    c.sweeps = h->timings().sweeps;
    c.acceleration = h->timings().acceleration;
    c.newton_krylov = h->timings().newton_krylov;
    c.newton_krylov_steps = h->timings().newton_krylov_steps;
    c.newton_krylov_iterations = h->timings().newton_krylov_iterations;
    c.newton_krylov_applications = h->timings().newton_krylov_applications;
    c.cycles = h->timings().cycles;
    if (const GlobalSolver* g = h->coarse_solver()) c.newton = g->timings();
  } else if (const GlobalSolver* g = deformer.global_solver()) {
    c.newton = g->timings();
  }
  return c;
}

double Breakdown::other() const {
  // The coarse phase contains the coarse Newton parts; the global method has no coarse phase.
  const double solver =
      restrict_prolong + sweeps + acceleration + newton_krylov + std::max(coarse, newton());
  return total - set_targets - vertex_update - solver;
}

void Breakdown::add_solver(const SolverClock& before, const SolverClock& after) {
  restrict_prolong += after.restrict_prolong - before.restrict_prolong;
  coarse += after.coarse - before.coarse;
  sweeps += after.sweeps - before.sweeps;
  acceleration += after.acceleration - before.acceleration;
  newton_krylov += after.newton_krylov - before.newton_krylov;
  newton_krylov_steps += after.newton_krylov_steps - before.newton_krylov_steps;
  newton_krylov_iterations += after.newton_krylov_iterations - before.newton_krylov_iterations;
  newton_krylov_applications +=
      after.newton_krylov_applications - before.newton_krylov_applications;
  assembly += after.newton.assembly - before.newton.assembly;
  factorization += after.newton.factorization - before.newton.factorization;
  solve += after.newton.solve - before.newton.solve;
  line_search += after.newton.line_search - before.newton.line_search;
  factorizations += after.newton.factorizations - before.newton.factorizations;
}

Breakdown Breakdown::per(int n) const {
  Breakdown b = *this;
  const double k = n > 0 ? 1.0 / n : 0.0;
  for (double* x :
       {&b.total, &b.set_targets, &b.restrict_prolong, &b.coarse, &b.assembly, &b.factorization,
        &b.solve, &b.line_search, &b.sweeps, &b.acceleration, &b.newton_krylov,
        &b.newton_krylov_steps, &b.newton_krylov_iterations, &b.newton_krylov_applications,
        &b.vertex_update, &b.factorizations})
    *x *= k;
  return b;
}

nlohmann::json Breakdown::to_json_ms() const {
  return {{"total", 1e3 * total},
          {"set_targets", 1e3 * set_targets},
          {"restrict_prolong", 1e3 * restrict_prolong},
          {"coarse", 1e3 * coarse},
          {"assembly", 1e3 * assembly},
          {"factorization", 1e3 * factorization},
          {"solve", 1e3 * solve},
          {"line_search", 1e3 * line_search},
          {"sweeps", 1e3 * sweeps},
          {"acceleration", 1e3 * acceleration},
          {"newton_krylov", 1e3 * newton_krylov},
          {"newton_krylov_steps", newton_krylov_steps},
          {"newton_krylov_iterations", newton_krylov_iterations},
          {"newton_krylov_applications", newton_krylov_applications},
          {"vertex_update", 1e3 * vertex_update},
          {"other", 1e3 * other()},
          {"factorizations", factorizations}};
}

void print_breakdown_row(const char* label, const Breakdown& b, SolveMethod method) {
  std::printf("  %-22s %9.2f %8.2f %8.2f", label, 1e3 * b.total, 1e3 * b.set_targets,
              1e3 * b.restrict_prolong);
  if (method == SolveMethod::Hierarchical)
    std::printf(" %8.2f", 1e3 * b.coarse);
  else
    std::printf(" %8s", "-");
  std::printf(" %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f\n", 1e3 * b.assembly,
              1e3 * b.factorization, 1e3 * b.solve, 1e3 * b.line_search, 1e3 * b.sweeps,
              1e3 * b.acceleration, 1e3 * b.newton_krylov, 1e3 * b.vertex_update, 1e3 * b.other());
}

}  // namespace primo::bench
