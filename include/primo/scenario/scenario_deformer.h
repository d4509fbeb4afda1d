#pragma once
// The deformer a resolved scenario describes, as `primo deform` and the benchmarks make it:
// its prisms, handles and forces, starting from the scenario's solved state when it has one
// (docs/scenario-format.md, `solved_state`), else from the format's starting state.

#include "primo/solve/deformer.h"
#include "primo/scenario/scenario.h"

namespace primo {

Deformer make_scenario_deformer(const Mesh& mesh, const ResolvedScenario& resolved);

}  // namespace primo
