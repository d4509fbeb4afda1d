#include "primo/scenario/scenario_solve.h"

namespace primo {

SolveMethod scenario_solve_method(SolverMethod from_scenario, size_t faces) {
  switch (from_scenario) {
    case SolverMethod::Local: return SolveMethod::Local;
    case SolverMethod::Global: return SolveMethod::Global;
    case SolverMethod::Hierarchical: return SolveMethod::Hierarchical;
    case SolverMethod::Default: break;
  }
  return default_solve_method(faces);
}

SolveMethod choose_solve_method(const std::string& flag, SolverMethod from_scenario, size_t faces) {
  if (flag == "local") return SolveMethod::Local;
  if (flag == "global") return SolveMethod::Global;
  if (flag == "hierarchical") return SolveMethod::Hierarchical;
  return scenario_solve_method(from_scenario, faces);
}

SolveOptions scenario_solve_options(const SolverSpec& solver, size_t faces,
                                    const std::string& flag) {
  SolveOptions options;
  options.method = choose_solve_method(flag, solver.method, faces);
  options.max_iterations = solver.max_iterations;
  options.tolerance = solver.tolerance;
  // No solver asked for: global Newton's minimum, reached through cheap hierarchical cycles.
  options.hierarchical_start = options.method == SolveMethod::Global && flag.empty() &&
                               solver.method == SolverMethod::Default;
  return options;
}

const char* solve_method_name(SolveMethod method) {
  switch (method) {
    case SolveMethod::Local: return "local";
    case SolveMethod::Hierarchical: return "hierarchical";
    case SolveMethod::Global: break;
  }
  return "global";
}

}  // namespace primo
