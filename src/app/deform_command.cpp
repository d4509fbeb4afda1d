// `primo deform SCENARIO.json -o OUT.ext [--stats STATS.json] [--solver global|local]`

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "primo/deformer.h"
#include "primo/error.h"
#include "primo/mesh_import.h"
#include "primo/mesh_io.h"
#include "primo/output_files.h"
#include "primo/scenario.h"
#include "primo/scenario_deformer.h"
#include "primo/scenario_solve.h"

namespace primo::app {
namespace {

struct DeformArguments {
  std::string scenario;
  std::string output;
  std::string stats;
  std::string solver;
  bool one_step = false;
};

int run_deform(const DeformArguments& args) {
  check_mesh_output_path(args.output);
  const Scenario scenario = load_scenario(args.scenario);
  // A scene file (glTF, FBX, ...) says what was joined, merged or left out: a note, not an error.
  LoadedMesh loaded = load_mesh_noted(scenario.mesh_path);
  if (!loaded.note.empty()) std::fprintf(stderr, "primo deform: note: %s\n", loaded.note.c_str());
  const Mesh mesh = std::move(loaded.mesh);
  const ResolvedScenario resolved = resolve_scenario(scenario, mesh);

  Deformer deformer = make_scenario_deformer(mesh, resolved);
  SolveOptions options = scenario_solve_options(resolved.solver, mesh.n_faces(), args.solver);
  // By default a large edit is followed in sub-steps (docs/engine.md, "Large steps");
  // --one-step solves from the format's starting state directly.
  options.path.enabled = !args.one_step;
  const SolveReport report = deformer.solve(options);

  const Mesh result = deformer.deformed_mesh(mesh);
  for (auto v : result.vertices())
    if (!result.point(v).allFinite())
      throw Error(args.scenario + ": the solve produced a non-finite position at vertex " +
                  std::to_string(v.idx()) + "; nothing was written");
  if (!std::isfinite(report.energy))
    throw Error(args.scenario + ": the solve produced a non-finite energy; nothing was written");

  std::string stats_text;
  if (!args.stats.empty()) {
    nlohmann::json stats = {
        {"energy", report.energy},
        {"initial_energy", report.initial_energy},
        {"iterations", report.iterations},
        {"converged", report.converged},
        {"stop_reason", report.stop_reason},
        {"seconds", report.seconds},
        {"faces", mesh.n_faces()},
        {"vertices", mesh.n_vertices()},
        {"solver", solve_method_name(options.method)},
        {"exact_newton_steps", report.exact_newton_steps},
        {"path_steps", report.path_steps},
        {"path_iterations", report.path_iterations},
        {"hierarchical_cycles", report.hierarchical_cycles},
        {"energies", report.energies},
    };
    stats_text = stats.dump(2) + "\n";
  }
  save_mesh(result, args.output);
  if (!args.stats.empty()) {
    try {
      write_text_atomically(args.stats, stats_text);
    } catch (const Error&) {
      std::remove(args.output.c_str());  // both results or neither
      throw;
    }
  }
  if (!report.converged)
    std::fprintf(stderr,
                 "primo deform: warning: %s: not converged after %d iterations (energy %.6g); "
                 "raise solver.max_iterations\n",
                 args.scenario.c_str(), report.iterations, report.energy);
  return 0;
}

}  // namespace

Command register_deform(CLI::App& app) {
  auto args = std::make_shared<DeformArguments>();
  CLI::App* cmd = app.add_subcommand("deform", "Solve a scenario file and write the deformed mesh");
  cmd->add_option("scenario", args->scenario, "Scenario file (primo-scenario/1 JSON)")->required();
  cmd->add_option("-o,--output", args->output, "Deformed mesh (.obj .off .ply .stl .om .gltf .glb)")
      ->required();
  cmd->add_option("--stats", args->stats, "Write solve statistics as JSON");
  cmd->add_option("--solver", args->solver,
                  "global, local or hierarchical (default: solver.method of the scenario, else "
                  "global up to 20,000 faces and hierarchical above)")
      ->check(CLI::IsMember({"global", "local", "hierarchical"}));
  cmd->add_flag("--one-step", args->one_step,
                "Solve from the scenario format's starting state (free prisms at rest, handles at "
                "their targets) in one step, instead of following large edits in sub-steps");
  return {cmd, [args] { return run_deform(*args); }};
}

}  // namespace primo::app
