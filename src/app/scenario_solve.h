#pragma once
// Solving a scenario the way `primo deform` does: the scenario's solver settings, the default
// solver for the mesh's size unless the scenario or a --solver flag names one. `primo bench
// quality` solves its cases through the same functions, so its figures are `deform`'s.

#include <string>

#include "primo/deformer.h"
#include "primo/scenario.h"

namespace primo::app {

// `flag` is a --solver value ("global", "local", "hierarchical") or "" for the scenario's
// `solver.method`, else the default for `faces` faces.
SolveMethod choose_solve_method(const std::string& flag, SolverMethod from_scenario, size_t faces);

// The scenario's iteration limit and tolerance with the chosen method; when neither names a
// method and the mesh is small enough for global Newton, a hierarchical start before it.
SolveOptions scenario_solve_options(const SolverSpec& solver, size_t faces,
                                    const std::string& flag = "");

const char* solve_method_name(SolveMethod method);  // "global", "local", "hierarchical"

}  // namespace primo::app
