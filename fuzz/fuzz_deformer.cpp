// libFuzzer target: a scenario set up on a small mesh as `primo deform` does (selections,
// regions, transforms, forces, solver settings: resolve_scenario, make_scenario_deformer) and a
// few solver iterations with the scenario's method. Every state must stay finite, or the solve
// must stop saying "not finite"; engine errors must be primo::Error.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/scenario/scenario.h"
#include "primo/scenario/scenario_deformer.h"
#include "primo/scenario/scenario_solve.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const primo::Mesh mesh = primo::make_bar(0.2, 1.0, 2, 6);
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const primo::Scenario scenario = primo::parse_scenario(text, "fuzz.json");
    const primo::ResolvedScenario resolved = primo::resolve_scenario(scenario, mesh);
    primo::Deformer deformer = primo::make_scenario_deformer(mesh, resolved);
    primo::SolveOptions options =
        primo::scenario_solve_options(resolved.solver, mesh.n_faces(), "");
    // Enough iterations at the final targets for a hierarchical solve from afar to reach its
    // Newton-Krylov steps (from the fourth on: HierarchicalOptions::newton_krylov_above).
    options.max_iterations = std::min(options.max_iterations, 6);
    options.max_hierarchical_cycles = 6;
    options.path.max_iterations = 6;  // a few sub-steps of a large edit, not all of them
    const primo::SolveReport report = deformer.solve(options);
    if (report.stop_reason == "not finite") return 0;
    for (size_t i = 1; i < report.energies.size(); ++i)
      if (!(report.energies[i] <= report.energies[i - 1] * (1 + 1e-9) + 1e-300)) std::abort();
    for (const primo::Vec3& p : deformer.vertex_positions())
      if (!p.allFinite()) std::abort();
  } catch (const primo::Error&) {
  }
  return 0;
}
