// `primo bench engine | drag | quality`: the benchmark group. Each benchmark lives in src/bench
// (docs/performance.md, docs/quality.md); this file only turns the command line into its
// options.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "bench/drag_bench.h"
#include "bench/engine_bench.h"
#include "bench/quality_bench.h"
#include "bench/scaling_bench.h"
#include "commands.h"
#include "number_options.h"

namespace primo::app {
namespace {

// `primo bench quality`'s options, into `options`.
CLI::App* add_quality_options(CLI::App& benchmarks, bench::QualityBenchOptions& options) {
  CLI::App* cmd = benchmarks.add_subcommand(
      "quality", "Large one-step edits: PriMo against CGAL's ARAP and SR-ARAP, with quality metrics");
  cmd->add_option("scenarios", options.scenarios,
                  "Scenario files to run (default: every case in assets/scenarios/quality)");
  cmd->add_option("--case", options.cases,
                  "Only this case (the scenario's file name without .json); repeatable");
  cmd->add_option("--json", options.json, "Also write every figure as JSON");
  cmd->add_option("--output-dir", options.output_dir,
                  "Write every result mesh as CASE-primo.obj, CASE-arap.obj, CASE-sr-arap.obj");
  cmd->add_option("--mesh-dir", options.mesh_dir,
                  "Where to find a scenario's mesh that is not at the scenario's own path (by "
                  "file name; default: a shared/meshes folder above the working directory or the "
                  "executable)");
  cmd->add_option("--peer-max-iterations", options.peer.max_iterations,
                  "Iteration cap of the ARAP peers (default 1000; their tolerance, 1e-6, ends "
                  "them earlier)")
      ->check(finite_range(1, 1000000));
  cmd->add_option("--half-thickness", options.half_thickness,
                  "PriMo's layer half-thickness as a fraction of the bounding-box diagonal "
                  "(default: the product's default material)")
      ->check(finite_range(0.0, 1.0));
  cmd->add_flag("--scenario-material", options.scenario_material,
                "Use each scenario's own prisms height instead of --half-thickness");
  return cmd;
}

}  // namespace

Command register_bench(CLI::App& app) {
  CLI::App* benchmarks = app.add_subcommand("bench", "Measure the engine's speed and convergence");
  benchmarks->require_subcommand(1);

  auto engine_args = std::make_shared<bench::EngineBenchOptions>();
  CLI::App* engine = benchmarks->add_subcommand(
      "engine", "Local/global throughput and iteration counts (cylinder), and a real-mesh solve");
  engine->add_option("--mesh", engine_args->mesh,
                     std::string("Real mesh for the large solve (default: shared/meshes/") +
                         bench::kEngineBenchMesh + ", searched upward from the working directory)");
  engine->add_option("--json", engine_args->json, "Also write the figures as JSON");
  engine->add_flag("--quick", engine_args->quick,
                   "Small cases only (600-face cylinder, no real mesh unless --mesh): seconds");

  auto drag_args = std::make_shared<bench::DragBenchOptions>();
  CLI::App* drag = benchmarks->add_subcommand(
      "drag", "Interactive drag: one solver iteration per frame, then on to convergence");
  drag->add_option("scenario", drag_args->scenario, "Scenario file (primo-scenario/1 JSON)")
      ->required();
  drag->add_option("--frames", drag_args->frames, "Frames from rest to the targets (default 60)")
      ->check(finite_range(1, 100000));
  drag->add_option("--solver", drag_args->solver,
                   "hierarchical (default), global or local; one iteration per frame")
      ->check(CLI::IsMember({"hierarchical", "global", "local"}));
  drag->add_option("--json", drag_args->json, "Also write the figures as JSON");
  drag->add_option("--mesh", drag_args->mesh,
                   "Use this mesh instead of the scenario's (a bare file name is also looked up "
                   "in shared/meshes above the working directory)");
  drag->add_option("--subdivide", drag_args->subdivide,
                   "Loop-subdivide the (triangle) mesh this many times first")
      ->check(finite_range(0, 4));
  drag->add_option("--shuffle", drag_args->shuffle,
                   "Then renumber the mesh's vertices and faces at random from this seed (not 0), "
                   "as another tool might write the same surface");
  drag->add_option("--frame-iterations", drag_args->frame_iterations,
                   "Solver iterations a frame, as the editor's batch where that many fit 50 ms "
                   "(hierarchical: the second is a Newton-Krylov step)")
      ->capture_default_str()
      ->check(finite_range(1, 8));
  drag->add_flag("--bbox-handles", drag_args->bbox_handles,
                 "Ignore the scenario's regions, handles and forces: bottom tenth (y) fixed, top "
                 "tenth turned 30 deg about x and moved a tenth of the diagonal along +z");
  drag->add_option("--lag-every", drag_args->lag_every,
                   "Measure the lag behind the converged shape every K frames and at the last "
                   "(0: the last only)")
      ->capture_default_str()
      ->check(finite_range(0, 100000));  // as --frames
  drag->add_flag("--lag-settle", drag_args->lag_settle,
                 "At the same frames, also the distance to where the mesh settles when the hand "
                 "stops there (solved on from the frame's state)");
  drag->add_option("--drag-prediction", drag_args->drag_prediction,
                   "Fraction of the last frame's change a frame starts from (0: none)")
      ->capture_default_str()
      ->check(finite_range(0.0, 2.0));
  drag->add_flag("--drag-only", drag_args->drag_only,
                 "Only the frames: no solving on to convergence, no full solve from rest");
  drag->add_flag("--preview", drag_args->preview,
                 "Frames show the drag's preview (coarse levels only, as the editor shows a "
                 "drag on a mesh whose cycles outlast a frame); the settle is the full "
                 "resolution catching up");
  drag->add_option("--preview-full-every", drag_args->preview_full_every,
                   "With --preview: every K frames one at full resolution (0: none)")
      ->capture_default_str()
      ->check(finite_range(0, 100000));
  drag->add_flag("--undo-redo", drag_args->undo_redo,
                 "After the settle: the targets back to rest and to the pose again, solved in "
                 "the editor's batches (an undo and a redo)");
  // Experiments with the hierarchical solver's settings (SolveOptions::hierarchical); the
  // defaults are the core's, which the editor and `primo deform` use.
  HierarchicalOptions& h = drag_args->hierarchical;
  const char* group = "Hierarchical solver settings (experiments; default: the core's)";
  drag->add_option("--cluster-size", h.hierarchy.cluster_size, "Bodies per cluster")
      ->check(finite_range(2, 1000))
      ->group(group);
  drag->add_option("--coarsest-max-bodies", h.hierarchy.coarsest_max_bodies,
                   "Coarsen until the coarsest level has at most this many bodies")
      ->check(finite_range(1, 10000000))
      ->group(group);
  drag->add_option("--preview-max-couplings", h.preview_max_couplings,
                   "With --preview: the finest coarse level with at most this many couplings")
      ->check(finite_range(0, 100000000))
      ->group(group);
  drag->add_option("--fine-sweeps", h.sweeps_per_level, "Local sweeps on the fine level per cycle")
      ->check(finite_range(0, 1000))
      ->group(group);
  drag->add_option("--intermediate-sweeps", h.intermediate_sweeps,
                   "Local sweeps on each intermediate level per cycle")
      ->check(finite_range(0, 1000))
      ->group(group);
  drag->add_option("--coarse-iterations", h.coarse_iterations,
                   "Newton iterations on the coarsest level per cycle")
      ->check(finite_range(0, 1000))
      ->group(group);
  drag->add_option("--intermediate-cycles", h.intermediate_cycles,
                   "Visits of the coarser levels per intermediate level (1: V-cycle, 2: W-cycle)")
      ->check(finite_range(1, 10))
      ->group(group);
  drag->add_option("--intermediate-relaxation", h.intermediate_relaxation,
                   "Over-relaxation factor of intermediate sweeps (1: plain Gauss-Seidel)")
      ->check(finite_range(1.0, 1.99))
      ->group(group);
  drag->add_option("--acceleration-history", h.acceleration_history,
                   "Anderson acceleration over this many cycles within one solve (0: off)")
      ->check(finite_range(0, 50))
      ->group(group);
  drag->add_option("--newton-krylov-below", h.newton_krylov_below,
                   "Newton-Krylov steps replace cycles once the targets stay put and a cycle "
                   "lowers the energy by less than this fraction (0: cycles only)")
      ->check(finite_range(0.0, 1.0))
      ->group(group);
  drag->add_option("--newton-krylov-above", h.newton_krylov_above,
                   "Newton-Krylov steps for the whole settle when, once the targets stay put, "
                   "a cycle still lowers the energy by more than this fraction (0: never)")
      ->check(finite_range(0.0, 1.0))
      ->group(group);
  drag->add_option("--newton-krylov-in-frames", h.newton_krylov_in_frames,
                   "A frame of two or more iterations makes its second a Newton-Krylov step "
                   "(0: cycles only)")
      ->group(group);
  drag->add_option("--krylov-stop-ratio", h.newton_krylov.stop_ratio,
                   "Conjugate gradients of a Newton-Krylov step stop after an iteration that "
                   "lowered the quadratic model by at most this fraction of the step's total")
      ->check(finite_range(1e-12, 0.99))
      ->group(group);
  drag->add_option("--krylov-max-turn", h.newton_krylov.max_turn,
                   "Largest turn of a body in one Newton-Krylov step, radians (0: no bound)")
      ->check(finite_range(0.0, 10.0))
      ->group(group);
  drag->add_option("--coarse-factor-reuse", h.coarse_factor_reuse,
                   "Coarse Newton steps per numeric factorization, beyond the first")
      ->check(finite_range(0, 100000))
      ->group(group);
  drag->add_option("--settle-factor-reuse", h.settle_factor_reuse,
                   "Coarse Newton steps per numeric factorization once a settle started near "
                   "the minimum (after a drag)")
      ->check(finite_range(0, 100000))
      ->group(group);
  drag->add_option("--drag-factor-reuse", h.drag_factor_reuse,
                   "During a drag: coarse Newton steps per numeric factorization, beyond the first")
      ->check(finite_range(0, 100000))
      ->group(group);
  drag->add_option("--drag-factor-lag", h.drag_factor_lag,
                   "During a drag: coarse steps a background refactorization has before its "
                   "factor takes over (-1: automatic, 0: refactorize in the foreground)")
      ->check(finite_range(-1, 100000))
      ->group(group);

  auto quality_args = std::make_shared<bench::QualityBenchOptions>();
  CLI::App* quality = add_quality_options(*benchmarks, *quality_args);

  auto scaling_args = std::make_shared<bench::ScalingBenchOptions>();
  CLI::App* scaling = benchmarks->add_subcommand(
      "scaling", "The same pull dragged on a mesh Loop-subdivided to about 60k, 240k, 1M and 4M "
                 "faces, in the file's order and renumbered (docs/performance.md)");
  scaling->add_option("scenario", scaling_args->scenario,
                      "Scenario of the pull (default: assets/scenarios/bench/bunny-ears.json)");
  scaling->add_option("--mesh", scaling_args->mesh,
                      "Use this triangle mesh instead of the scenario's (a bare file name is also "
                      "looked up in shared/meshes)");
  scaling->add_option("--steps", scaling_args->steps, "Loop steps, one size each")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(0, 4));
  scaling->add_flag("--bbox-handles", scaling_args->bbox_handles,
                    "The bounding-box pull of `bench drag --bbox-handles` instead of the "
                    "scenario's handles");
  scaling->add_option("--frames", scaling_args->frames, "Frames of each drag")
      ->capture_default_str()
      ->check(finite_range(1, 100000));
  scaling->add_option("--seed", scaling_args->seed, "Seed of the renumbered copies (not 0)")
      ->capture_default_str();
  scaling->add_flag("--ordered-only", scaling_args->ordered_only,
                    "Only the file's order, no renumbered copies");
  scaling->add_option("--json", scaling_args->json, "Also write every figure as JSON");

  return {benchmarks, [engine, engine_args, drag, drag_args, quality, quality_args, scaling,
                       scaling_args]() -> int {
            if (engine->parsed()) return bench::run_engine_bench(*engine_args);
            if (drag->parsed()) return bench::run_drag_bench(*drag_args);
            if (quality->parsed()) return bench::run_quality_bench(*quality_args);
            if (scaling->parsed()) return bench::run_scaling_bench(*scaling_args);
            return 1;  // require_subcommand(1) makes this unreachable
          }};
}

}  // namespace primo::app
