// `primo deform SCENARIO.json -o OUT.ext [--stats STATS.json] [--solver global|local]`

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <vector>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "rethrow_naming.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "primo/scenario/scenario.h"
#include "primo/scenario/scenario_deformer.h"
#include "primo/scenario/scenario_solve.h"

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
  // Every output is checked before any work: its folder, not a special file, and not the same
  // file as another output or an input (-o over the input mesh would destroy it).
  check_mesh_output_path(args.output);
  if (!args.stats.empty()) check_output_path(args.stats);
  const std::vector<NamedFile> outputs = {{"-o", args.output}, {"--stats", args.stats}};
  check_distinct_files(outputs, {{"the scenario", args.scenario}});
  const Scenario scenario = load_scenario(args.scenario);
  check_distinct_files(outputs, {{"the scenario", args.scenario}, {"the scenario's mesh", scenario.mesh_path}});
  // A scene file (glTF, FBX, ...) says what was joined, merged or left out: a note, not an error.
  LoadedMesh loaded = load_mesh_noted(scenario.mesh_path);
  if (!loaded.note.empty()) std::fprintf(stderr, "primo deform: note: %s\n", loaded.note.c_str());
  const Mesh mesh = std::move(loaded.mesh);

  Mesh result;
  SolveReport report;
  SolveOptions options;
  try {
    const ResolvedScenario resolved = resolve_scenario(scenario, mesh);
    Deformer deformer = make_scenario_deformer(mesh, resolved);
    options = scenario_solve_options(resolved.solver, mesh.n_faces(), args.solver);
    // By default a large edit is followed in sub-steps (docs/engine.md, "Large steps");
    // --one-step solves from the format's starting state directly.
    options.path.enabled = !args.one_step;
    report = deformer.solve(options);
    result = deformer.deformed_mesh(mesh);
  } catch (...) {
    rethrow_naming(args.scenario);
  }
  if (report.stop_reason == "not finite")
    throw Error(args.scenario + ": the solve produced a non-finite value after " +
                std::to_string(report.iterations) +
                " iterations (a setting too large?); nothing was written");
  for (auto v : result.vertices())
    if (!result.point(v).allFinite())
      throw Error(args.scenario + ": the solve produced a non-finite position at vertex " +
                  std::to_string(v.idx()) + "; nothing was written");
  if (!std::isfinite(report.energy))
    throw Error(args.scenario + ": the solve produced a non-finite energy; nothing was written");

  // Both results or neither: staged beside their targets, renamed only when both are complete.
  StagedOutputs out;
  // UVs, materials, colours and normal structure as read; only positions and normals change.
  out.stage_mesh(args.output, result, loaded.attributes);
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
    out.stage(args.stats, stats.dump(2) + "\n");
  }
  out.commit();
  // A format that cannot hold the skin says so; the mesh itself is written.
  if (const std::string lost = save_note(loaded.attributes, args.output); !lost.empty())
    std::fprintf(stderr, "primo deform: note: %s\n", lost.c_str());
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
