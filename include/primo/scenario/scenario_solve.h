#pragma once
// Solving a scenario the way `primo deform` does: the scenario's solver settings, the default
// solver for the mesh's size unless the scenario or a --solver flag names one. `primo bench
// quality`, `primo replay` and the editor choose their method through the same functions, so
// that all of them end at the same result.

#include <string>

#include "primo/solve/deformer.h"
#include "primo/scenario/scenario.h"

namespace primo {

// The method `from_scenario` (a scenario's or a session's solver.method) names, else the
// default for `faces` faces (default_solve_method: global Newton up to 20,000 faces,
// hierarchical above). The one place that maps one to the other.
SolveMethod scenario_solve_method(SolverMethod from_scenario, size_t faces);

// `flag` is a --solver value ("global", "local", "hierarchical") or "" for
// scenario_solve_method.
SolveMethod choose_solve_method(const std::string& flag, SolverMethod from_scenario, size_t faces);

// The scenario's iteration limit and tolerance with the chosen method; when neither names a
// method and the mesh is small enough for global Newton, a hierarchical start before it.
SolveOptions scenario_solve_options(const SolverSpec& solver, size_t faces,
                                    const std::string& flag = "");

const char* solve_method_name(SolveMethod method);  // "global", "local", "hierarchical"

}  // namespace primo
