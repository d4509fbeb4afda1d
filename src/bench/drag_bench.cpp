#include "drag_bench.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "drag_profile.h"
#include "inputs.h"
#include "machine.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/solve/hierarchical_solver.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_order.h"
#include "primo/mesh/mesh_subdivision.h"
#include "primo/io/output_files.h"
#include "primo/scenario/scenario.h"
#include "primo/scenario/scenario_solve.h"
#include "reach_pose.h"
#include "report.h"

namespace fs = std::filesystem;

namespace primo::bench {
namespace {

constexpr double kDragConvergeTolerance = 1e-7;
// The shapes a frame's lag is measured against. The settle's tolerance above (the editor's)
// can stop where the energy is flat 0.1-0.2% of the diagonal short of the minimum (the koala's
// last frame: 0.087% for the drag's settle, 0.18% with three cycles a frame, against 0.001%
// at 1e-10), which would blur a lag criterion of 0.5%.
constexpr double kLagReferenceTolerance = 1e-10;
constexpr int kDragConvergeMaxIterations = 5000;
constexpr double kPerceivedGap = 0.01;  // "within 1% of the converged energy"

// A handle's way from rest to its target: transform(s) for s in [0, 1], the rotation angle
// and the translation scaled by s about the same centre. s = 1 gives the scenario's transform.
struct HandlePath {
  Vec3 translate = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  double angle_deg = 0.0;
  Vec3 center = Vec3::Zero();

  RigidTransform at(double s) const {
    return make_rigid_transform(s * translate, axis, s * angle_deg, center);
  }
};

// Everything the runs need: the mesh after --mesh/--subdivide, prisms, handles at their final
// transforms with their paths, and forces at their final offsets.
struct DragCase {
  std::string mesh_path;
  Mesh mesh;
  double load_seconds = 0.0;
  double subdivide_seconds = 0.0;
  std::string handles_from;
  PrismParameters prisms;
  std::vector<Handle> handles;
  std::vector<HandlePath> paths;
  std::vector<Force> forces;
};

// --- Setting up ---------------------------------------------------------------------------------

DragCase make_drag_case(const Scenario& scenario, const std::string& mesh_path,
                        const DragBenchOptions& args) {
  DragCase c;
  c.mesh_path = mesh_path;
  auto start = Clock::now();
  c.mesh = load_mesh(mesh_path);
  c.load_seconds = seconds_since(start);
  if (args.subdivide > 0) {
    start = Clock::now();
    c.mesh = loop_subdivide(c.mesh, args.subdivide, mesh_path);
    c.subdivide_seconds = seconds_since(start);
  }
  if (args.shuffle != 0) c.mesh = shuffled_mesh(c.mesh, args.shuffle);

  if (args.bbox_handles) {
    // Only the scenario's global prism parameters are kept: its regions, handles and forces
    // select faces of its own mesh.
    Scenario prisms_only = scenario;
    prisms_only.regions.clear();
    prisms_only.handles.clear();
    prisms_only.forces.clear();
    c.prisms = resolve_scenario(prisms_only, c.mesh).prisms;
    const ReachPose pose = make_reach_pose(c.mesh, mesh_path);
    c.handles = pose.handles();
    c.paths = {HandlePath{}, HandlePath{pose.translate, pose.axis, pose.angle_deg,
                                        pose.top_centroid}};
    c.handles_from = "bounding box (--bbox-handles)";
    return c;
  }

  ResolvedScenario resolved = resolve_scenario(scenario, c.mesh);
  c.prisms = std::move(resolved.prisms);
  c.handles = std::move(resolved.handles);
  c.forces = std::move(resolved.forces);
  const FaceGeometry geometry = compute_face_geometry(c.mesh);
  for (size_t i = 0; i < c.handles.size(); ++i) {
    const TransformSpec& t = scenario.handles[i].transform;
    c.paths.push_back({t.translate, t.axis, t.angle_deg,
                       t.center ? *t.center : area_weighted_centroid(geometry, c.handles[i].faces)});
  }
  c.handles_from = "scenario";
  return c;
}

SolveMethod drag_method(const std::string& name) {
  if (name == "global") return SolveMethod::Global;
  if (name == "local") return SolveMethod::Local;
  return SolveMethod::Hierarchical;
}

// --- Measuring ----------------------------------------------------------------------------------

struct DragRun {
  int faces = 0;
  int vertices = 0;
  double setup_seconds = 0.0;  // Deformer construction
  double solver_setup_seconds = 0.0;  // Deformer::prepare: hierarchy, symbolic analysis
  std::vector<double> frame_seconds;
  std::vector<double> frame_page_faults;  // minor page faults in each frame
  std::vector<double> frame_energies;
  Breakdown first_frame;
  Breakdown later_frames;  // sum over frames 2..N
  double energy_evaluation_seconds = 0.0;
  int drag_factor_lag = 0;  // steps of the background refreshes during the drag
  int foreground_factorizations = 0, background_factorizations = 0;  // during the drag
  double background_factorization_seconds = 0.0;
  std::vector<int> level_bodies;  // hierarchical: bodies per level, fine first
  int preview_level = -1;         // --preview: the level the frames were solved on
  int preview_couplings = 0;
  SolveReport converge;
  Breakdown converge_profile;
  double memory_after_drag_mb = 0.0;
  double memory_after_converge_mb = 0.0;
  // The drag's mesh at the lag checkpoints (frame numbers from 1).
  std::vector<int> checkpoint_frames;
  std::vector<std::vector<Vec3>> checkpoint_positions;
  std::vector<std::vector<RigidTransform>> checkpoint_motions;  // with --lag-settle only
};

// How far the drag's mesh at a frame is from the converged shape for that frame's targets.
struct LagPoint {
  int frame = 0;
  double energy = 0.0, converged_energy = 0.0;
  double max_distance = 0.0;  // as a fraction of the bounding-box diagonal
  int iterations = 0;         // the reference solve's, from the previous checkpoint's shape
  // --lag-settle: the frame's own state solved on with its targets held (-1: not measured).
  double settle_distance = -1.0, settle_energy = 0.0;
  int settle_iterations = 0;
};

struct JumpRun {  // an undo or a redo
  int calls = 0, iterations = 0, path_steps = 0, path_iterations = 0;
  int newton_krylov_steps = 0;
  double seconds = 0.0, energy = 0.0;
  bool converged = false;
};

struct FullSolveRun {
  double setup_seconds = 0.0;
  double hierarchy_build_seconds = -1.0;  // hierarchical only, timed on a separate solver
  SolveReport report;
  Breakdown profile;
  int iterations_to_perceived = -1;
  double seconds_to_perceived = -1.0;
  double memory_after_mb = 0.0;
};

void set_targets(Deformer& deformer, const DragCase& c, double s) {
  for (size_t i = 0; i < c.paths.size(); ++i) deformer.set_handle_transform(int(i), c.paths[i].at(s));
  for (size_t j = 0; j < c.forces.size(); ++j)
    deformer.set_force_offset(int(j), s * c.forces[j].target_offset);
}

double g_sink = 0.0;  // keeps the vertex read from being optimized away

// Pages the kernel faulted in for this process so far without reading a disk: memory touched
// for the first time, which a frame that allocates afresh pays for on every call.
long minor_page_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// The drag on `deformer` (made with the final targets): targets back to rest, then N frames.
void run_frames(Deformer& deformer, const DragCase& c, const SolveOptions& base, int frames,
                int frame_iterations, int lag_every, bool keep_motions, bool preview,
                int full_every, DragRun& run) {
  set_targets(deformer, c, 0.0);  // every handle and force back at rest
  deformer.reset();
  // The editor sets the solver up when the handles are made, before they are dragged.
  const auto setup_start = Clock::now();
  deformer.prepare(base);
  run.solver_setup_seconds = seconds_since(setup_start);
  const SolverClock after_setup = SolverClock::read(deformer);

  SolveOptions frame = base;
  frame.max_iterations = frame_iterations;
  frame.drag_frame = true;
  frame.tolerance = 0.0;
  std::vector<Vec3> positions;  // one buffer for every frame, as the editor keeps
  for (int k = 1; k <= frames; ++k) {
    const SolverClock before = SolverClock::read(deformer);
    const long faults_before = minor_page_faults();
    const auto t0 = Clock::now();
    set_targets(deformer, c, double(k) / frames);
    const auto t1 = Clock::now();
    const bool full = !preview || (full_every > 0 && k % full_every == 0);
    const SolveReport report = full ? deformer.solve(frame) : deformer.preview(frame);
    const auto t2 = Clock::now();
    deformer.vertex_positions(positions);
    const auto t3 = Clock::now();
    run.frame_page_faults.push_back(double(minor_page_faults() - faults_before));
    g_sink += positions.empty() ? 0.0 : positions.back().x();

    Breakdown& b = k == 1 ? run.first_frame : run.later_frames;
    b.total += std::chrono::duration<double>(t3 - t0).count();
    b.set_targets += std::chrono::duration<double>(t1 - t0).count();
    b.vertex_update += std::chrono::duration<double>(t3 - t2).count();
    b.add_solver(before, SolverClock::read(deformer));
    run.frame_seconds.push_back(std::chrono::duration<double>(t3 - t0).count());
    run.frame_energies.push_back(report.energy);
    if (k == frames || (lag_every > 0 && k % lag_every == 0)) {
      run.checkpoint_frames.push_back(k);
      run.checkpoint_positions.push_back(positions);
      if (keep_motions) run.checkpoint_motions.push_back(deformer.face_motions());
    }
  }
  if (const HierarchicalSolver* h = deformer.hierarchical_solver()) {
    for (int l = 0; l < h->levels(); ++l) run.level_bodies.push_back(h->bodies(l));
    run.drag_factor_lag = h->drag_factor_lag();
    if (preview) {
      run.preview_level = h->previewing() ? h->preview_level() : h->automatic_preview_level();
      run.preview_couplings = int(h->system(run.preview_level).couplings.size());
    }
  }
  const SolverClock after_drag = SolverClock::read(deformer);
  run.foreground_factorizations =
      after_drag.newton.factorizations - after_setup.newton.factorizations;
  run.background_factorizations = after_drag.newton.background_factorizations;
  run.background_factorization_seconds = after_drag.newton.background_factorization;

  // One pass over all joints, for reading "other": a hierarchical cycle makes one after its
  // sweeps (Deformer::solve carries the energy through handle moves instead of a pass).
  const auto start = Clock::now();
  constexpr int kEvaluations = 5;
  for (int i = 0; i < kEvaluations; ++i)
    g_sink += deformer.system().energy(deformer.body_states());
  run.energy_evaluation_seconds = seconds_since(start) / kEvaluations;
  run.memory_after_drag_mb = peak_memory_mb();
}

// After the last frame: on with the same method to the convergence tolerance.
void run_converge(Deformer& deformer, const SolveOptions& base, DragRun& run) {
  SolveOptions converge = base;
  converge.max_iterations = kDragConvergeMaxIterations;
  converge.tolerance = kDragConvergeTolerance;
  const SolverClock before = SolverClock::read(deformer);
  const auto start = Clock::now();
  run.converge = deformer.solve(converge);
  run.converge_profile.total = seconds_since(start);
  run.converge_profile.add_solver(before, SolverClock::read(deformer));
  run.memory_after_converge_mb = peak_memory_mb();
}

// The targets jump to `s` of the way (0: rest) and are solved as the editor's solver thread
// solves an undo or a redo of a big mesh's drag: its first two batches come within 0.3 s of
// the request and are one iteration each (one outlasts the 50 ms a drag's batch may take),
// later ones four (solver_worker.cpp), to the editor's tolerance.
JumpRun run_jump(Deformer& deformer, const DragCase& c, const SolveOptions& base, double s) {
  constexpr int kFirstBatches = 2, kFirstBatch = 1, kSettleBatch = 4, kMaxCalls = 5000;
  SolveOptions options = base;
  options.tolerance = SolveOptions{}.tolerance;
  options.path.enabled = true;
  set_targets(deformer, c, s);
  const SolverClock before = SolverClock::read(deformer);
  JumpRun run;
  SolveReport report;
  do {
    const int batch = run.calls < kFirstBatches ? kFirstBatch : kSettleBatch;
    options.max_iterations = batch;
    options.path.max_iterations = batch;
    report = deformer.solve(options);
    run.iterations += report.iterations;
    run.path_steps += report.path_steps;
    run.path_iterations += report.path_iterations;
    run.seconds += report.seconds;
    ++run.calls;
  } while (!report.converged && run.calls < kMaxCalls);
  run.energy = report.energy;
  run.converged = report.converged;
  run.newton_krylov_steps =
      SolverClock::read(deformer).newton_krylov_steps - before.newton_krylov_steps;
  return run;
}

// The reference: a second deformer dragged through the same targets, converged at every
// checkpoint (warm-started from the previous one), against the drag's recorded meshes. With
// the drag's states recorded (--lag-settle), each is also solved on where it is.
std::vector<LagPoint> measure_lag(const DragCase& c, const SolveOptions& base, int frames,
                                  const DragRun& run) {
  std::vector<LagPoint> lag;
  Deformer reference(c.mesh, c.prisms, c.handles, c.forces);
  set_targets(reference, c, 0.0);
  reference.reset();
  SolveOptions converge = base;
  converge.max_iterations = kDragConvergeMaxIterations;
  converge.tolerance = kLagReferenceTolerance;
  SolveOptions settle = converge;
  converge.path.enabled = true;  // a checkpoint is several frames away: follow, as a drag does
  const double diagonal = bounding_box_diagonal(c.mesh);
  // A deformer of its own, so that the reference's solves are the same with or without it.
  std::unique_ptr<Deformer> settler;
  if (!run.checkpoint_motions.empty())
    settler = std::make_unique<Deformer>(c.mesh, c.prisms, c.handles, c.forces);
  for (size_t i = 0; i < run.checkpoint_frames.size(); ++i) {
    const int k = run.checkpoint_frames[i];
    set_targets(reference, c, double(k) / frames);
    const SolveReport report = reference.solve(converge);
    const std::vector<Vec3>& dragged = run.checkpoint_positions[i];
    LagPoint point{k, run.frame_energies[size_t(k) - 1], report.energy,
                   largest_point_distance(reference.vertex_positions(), dragged) / diagonal,
                   report.iterations};
    if (settler) {
      set_targets(*settler, c, double(k) / frames);
      settler->set_face_motions(run.checkpoint_motions[i]);
      const SolveReport settled = settler->solve(settle);
      point.settle_distance =
          largest_point_distance(settler->vertex_positions(), dragged) / diagonal;
      point.settle_energy = settled.energy;
      point.settle_iterations = settled.iterations;
    }
    lag.push_back(point);
  }
  return lag;
}

// A fresh deformer with the final targets (its initial state), solved to convergence; then,
// on another fresh one, the same solve cut off at the first iteration within 1% of the
// converged energy, timed: the iterations are deterministic, so it is the same path.
FullSolveRun run_full_solve(const DragCase& c, const SolveOptions& base) {
  FullSolveRun run;
  const SolveMethod method = base.method;
  SolveOptions options = base;
  options.max_iterations = kDragConvergeMaxIterations;
  options.tolerance = kDragConvergeTolerance;
  {
    auto start = Clock::now();
    Deformer deformer(c.mesh, c.prisms, c.handles, c.forces);
    run.setup_seconds = seconds_since(start);
    if (method == SolveMethod::Hierarchical) {
      start = Clock::now();
      { HierarchicalSolver build_only(deformer.system(), options.hierarchical); }
      run.hierarchy_build_seconds = seconds_since(start);
    }
    const SolverClock before = SolverClock::read(deformer);
    start = Clock::now();
    run.report = deformer.solve(options);
    run.profile.total = seconds_since(start);
    run.profile.add_solver(before, SolverClock::read(deformer));
  }
  const double target = (1.0 + kPerceivedGap) * run.report.energy;
  for (size_t k = 0; k < run.report.energies.size(); ++k)
    if (run.report.energies[k] <= target) {
      run.iterations_to_perceived = int(k) + 1;
      break;
    }
  if (run.report.initial_energy <= target) run.iterations_to_perceived = 0;
  if (run.iterations_to_perceived > 0) {
    Deformer deformer(c.mesh, c.prisms, c.handles, c.forces);
    SolveOptions cut = options;
    cut.max_iterations = run.iterations_to_perceived;
    run.seconds_to_perceived = deformer.solve(cut).seconds;
  } else if (run.iterations_to_perceived == 0) {
    run.seconds_to_perceived = 0.0;
  }
  run.memory_after_mb = peak_memory_mb();
  return run;
}

}  // namespace

int run_drag_bench(const DragBenchOptions& args) {
  check_json_folder(args.json);
  const Scenario scenario = load_scenario(args.scenario);
  const SolveMethod method = drag_method(args.solver);
  const std::string build = build_label();
  const std::vector<double> load_before = load_average();
  const char* blas_threads = std::getenv("OPENBLAS_NUM_THREADS");

  nlohmann::json out;
  out["scenario"] = args.scenario;
  out["build"] = build;
  out["solver"] = solve_method_name(method);
  out["frames"] = args.frames;
  out["frame_iterations"] = args.frame_iterations;
  out["preview"] = args.preview;
  out["preview_full_every"] = args.preview_full_every;
  out["subdivide"] = args.subdivide;
  out["shuffle"] = args.shuffle;
  out["bbox_handles"] = args.bbox_handles;
  out["drag_prediction"] = args.drag_prediction;
  std::printf("primo bench drag %s  [build: %s]\n\n", args.scenario.c_str(), build.c_str());

  std::string mesh_path = scenario.mesh_path;
  if (!args.mesh.empty()) {
    mesh_path = locate_mesh(args.mesh);
    if (mesh_path.empty() && fs::path(args.mesh).has_parent_path())
      throw Error(args.mesh + ": no such mesh file");
    if (mesh_path.empty()) {  // a shared mesh that is not there: skip, as bench engine does
      const std::string skipped = "skipped: " + args.mesh +
                                  " not found (neither as a path nor in a shared/meshes folder "
                                  "above the working directory or the executable)";
      std::printf("%s\n", skipped.c_str());
      out["skipped"] = skipped;
      if (!args.json.empty()) write_text_atomically(args.json, out.dump(2) + "\n");
      return 0;
    }
  }

  const DragCase c = make_drag_case(scenario, mesh_path, args);
  const double memory_after_mesh = peak_memory_mb();
  std::printf("Mesh       %s", mesh_path.c_str());
  if (args.subdivide > 0) std::printf(" + %d Loop steps", args.subdivide);
  if (args.shuffle != 0)
    std::printf(", renumbered at random (seed %llu)", (unsigned long long)args.shuffle);
  std::printf(": %d faces, %d vertices (load %.2f s", int(c.mesh.n_faces()),
              int(c.mesh.n_vertices()), c.load_seconds);
  if (args.subdivide > 0) std::printf(", subdivide %.2f s", c.subdivide_seconds);
  std::printf(")\n");
  std::printf("Handles    from the %s:", c.handles_from.c_str());
  for (const Handle& h : c.handles)
    std::printf(" %s (%zu faces)", h.name.empty() ? "-" : h.name.c_str(), h.faces.size());
  std::printf("; %zu forces\n", c.forces.size());
  std::printf("Solver     %s, %d frames of %d iteration%s each, drag prediction %g%s\n",
              solve_method_name(method), args.frames, args.frame_iterations,
              args.frame_iterations == 1 ? "" : "s", args.drag_prediction,
              args.drag_only ? " (--drag-only)" : "");
  SolveOptions base;
  base.method = method;
  base.hierarchical = args.hierarchical;
  base.drag_prediction = args.drag_prediction;
  // The full solve from rest is the one-step solve the drag's figures have always been
  // compared with (docs/performance.md); a drag's frames are small steps either way.
  base.path.enabled = false;
  const HierarchicalOptions defaults;
  const bool tuned =
      args.hierarchical.hierarchy.coarsest_max_bodies != defaults.hierarchy.coarsest_max_bodies ||
      args.hierarchical.hierarchy.cluster_size != defaults.hierarchy.cluster_size ||
      args.hierarchical.sweeps_per_level != defaults.sweeps_per_level ||
      args.hierarchical.intermediate_sweeps != defaults.intermediate_sweeps ||
      args.hierarchical.coarse_iterations != defaults.coarse_iterations ||
      args.hierarchical.intermediate_cycles != defaults.intermediate_cycles ||
      args.hierarchical.coarse_factor_reuse != defaults.coarse_factor_reuse ||
      args.hierarchical.settle_factor_reuse != defaults.settle_factor_reuse ||
      args.hierarchical.drag_factor_reuse != defaults.drag_factor_reuse ||
      args.hierarchical.drag_factor_lag != defaults.drag_factor_lag ||
      args.hierarchical.intermediate_relaxation != defaults.intermediate_relaxation ||
      args.hierarchical.acceleration_history != defaults.acceleration_history ||
      args.hierarchical.newton_krylov_below != defaults.newton_krylov_below ||
      args.hierarchical.newton_krylov_above != defaults.newton_krylov_above ||
      args.hierarchical.newton_krylov_in_frames != defaults.newton_krylov_in_frames ||
      args.hierarchical.newton_krylov.stop_ratio != defaults.newton_krylov.stop_ratio ||
      args.hierarchical.newton_krylov.max_turn != defaults.newton_krylov.max_turn;
  const nlohmann::json settings = {
      {"cluster_size", args.hierarchical.hierarchy.cluster_size},
      {"coarsest_max_bodies", args.hierarchical.hierarchy.coarsest_max_bodies},
      {"fine_sweeps", args.hierarchical.sweeps_per_level},
      {"intermediate_sweeps", args.hierarchical.intermediate_sweeps},
      {"coarse_iterations", args.hierarchical.coarse_iterations},
      {"intermediate_cycles", args.hierarchical.intermediate_cycles},
      {"coarse_factor_reuse", args.hierarchical.coarse_factor_reuse},
      {"settle_factor_reuse", args.hierarchical.settle_factor_reuse},
      {"drag_factor_reuse", args.hierarchical.drag_factor_reuse},
      {"drag_factor_lag", args.hierarchical.drag_factor_lag},
      {"intermediate_relaxation", args.hierarchical.intermediate_relaxation},
      {"acceleration_history", args.hierarchical.acceleration_history},
      {"newton_krylov_below", args.hierarchical.newton_krylov_below},
      {"newton_krylov_above", args.hierarchical.newton_krylov_above},
      {"newton_krylov_in_frames", args.hierarchical.newton_krylov_in_frames},
      {"krylov_stop_ratio", args.hierarchical.newton_krylov.stop_ratio},
      {"krylov_max_turn", args.hierarchical.newton_krylov.max_turn},
      {"core_defaults", !tuned}};
  if (method == SolveMethod::Hierarchical) {
    out["hierarchical_settings"] = settings;
    std::string drag_refresh;
    if (args.hierarchical.drag_factor_lag != 0) {
      drag_refresh = "; during a drag " + std::to_string(args.hierarchical.drag_factor_reuse) +
                     " times, refreshed in the background";
      if (args.hierarchical.drag_factor_lag > 0)
        drag_refresh += " for " + std::to_string(args.hierarchical.drag_factor_lag) + " steps";
    }
    std::printf("           hierarchy: clusters of %d, coarsest <= %d bodies, %d fine sweeps, %d "
                "intermediate sweeps x %d visits, %d coarse Newton iterations per cycle, a "
                "coarse factorization reused up to %d times (%d in a settle after a drag)%s%s\n",
                args.hierarchical.hierarchy.cluster_size,
                args.hierarchical.hierarchy.coarsest_max_bodies,
                args.hierarchical.sweeps_per_level, args.hierarchical.intermediate_sweeps,
                args.hierarchical.intermediate_cycles, args.hierarchical.coarse_iterations,
                args.hierarchical.coarse_factor_reuse, args.hierarchical.settle_factor_reuse,
                drag_refresh.c_str(),
                tuned ? " (NOT the core's defaults)" : "");
  }
  std::printf("\n");
  std::fflush(stdout);

  // 1: the drag, then on to convergence.
  DragRun drag;
  drag.faces = int(c.mesh.n_faces());
  drag.vertices = int(c.mesh.n_vertices());
  {
    const auto start = Clock::now();
    // Held by pointer so that it can go before the lag's reference deformer is made: two
    // deformers alive at once would put the run's peak memory at twice the editor's.
    auto deformer = std::make_unique<Deformer>(c.mesh, c.prisms, c.handles, c.forces);
    drag.setup_seconds = seconds_since(start);
    run_frames(*deformer, c, base, args.frames, args.frame_iterations,
               args.drag_only ? 0 : args.lag_every, args.lag_settle && !args.drag_only,
               args.preview, args.preview_full_every, drag);

    const double median_ms = 1e3 * median_of(drag.frame_seconds);
    const double max_ms =
        1e3 * *std::max_element(drag.frame_seconds.begin(), drag.frame_seconds.end());
    const double max_later_ms =
        drag.frame_seconds.size() > 1
            ? 1e3 * *std::max_element(drag.frame_seconds.begin() + 1, drag.frame_seconds.end())
            : max_ms;
    if (!drag.level_bodies.empty()) {
      std::printf("Hierarchy  %zu levels, bodies:", drag.level_bodies.size());
      for (size_t l = 0; l < drag.level_bodies.size(); ++l)
        std::printf("%s %d", l ? " ->" : "", drag.level_bodies[l]);
      if (drag.drag_factor_lag > 0)
        std::printf("; coarse factors refreshed in the background during the drag, taking over "
                    "%d coarse steps later", drag.drag_factor_lag);
      std::printf("\n");
      if (drag.preview_level > 0)
        std::printf("Preview    the frames solved level %d only (%d bodies, %d couplings), "
                    "the fine level from the settle on\n",
                    drag.preview_level, drag.level_bodies[size_t(drag.preview_level)],
                    drag.preview_couplings);
      std::printf("\n");
      out["drag_factor_lag"] = drag.drag_factor_lag;
      out["preview_level"] = drag.preview_level;
    }
    std::printf("Drag (%d frames; deformer setup %.3f s and solver setup %.3f s before the "
                "drag, as in the editor, not in the frames)\n",
                args.frames, drag.setup_seconds, drag.solver_setup_seconds);
    std::printf("  %8s %10s %10s %10s %10s %14s\n", "faces", "median ms", "max ms", "first ms",
                "max 2..N", "final energy");
    std::printf("  %8d %10.2f %10.2f %10.2f %10.2f %14.6e\n\n", drag.faces, median_ms, max_ms,
                1e3 * drag.frame_seconds.front(), max_later_ms, drag.frame_energies.back());
    std::fflush(stdout);
    out["frame_seconds"] = drag.frame_seconds;
    out["frame_energies"] = drag.frame_energies;
    out["median_ms"] = median_ms;
    // Frames 2..N: the first also touches what the drag's state vectors need once.
    const double faults =
        drag.frame_page_faults.size() > 1
            ? median_of(std::vector<double>(drag.frame_page_faults.begin() + 1, drag.frame_page_faults.end()))
            : drag.frame_page_faults.front();
    std::printf("  page faults a frame (median of frames 2..N): %.0f (%.1f MB of fresh pages)\n\n",
                faults, faults * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0));
    out["page_faults_per_frame"] = faults;
    out["max_ms"] = max_ms;
    out["first_frame_ms"] = 1e3 * drag.frame_seconds.front();
    out["max_ms_after_first"] = max_later_ms;
    out["final_energy"] = drag.frame_energies.back();

    if (!args.drag_only) {
      run_converge(*deformer, base, drag);
      const double final_energy = drag.frame_energies.back();
      const double converged = drag.converge.energy;
      const double gap = converged > 0 ? final_energy / converged - 1.0 : 0.0;
      std::printf("Solving on after the last frame (relative change %.0e, at most %d iterations)\n",
                  kDragConvergeTolerance, kDragConvergeMaxIterations);
      std::printf("  %14s %14s %10s %10s %6s  %s\n", "final energy", "converged E", "gap %",
                  "seconds", "iters", "stop");
      std::printf("  %14.6e %14.6e %10.3f %10.3f %6d  %s\n\n", final_energy, converged,
                  100.0 * gap, drag.converge.seconds, drag.converge.iterations,
                  drag.converge.stop_reason.c_str());
      out["converged_energy"] = converged;
      out["final_gap"] = gap;
      out["converge_seconds"] = drag.converge.seconds;
      out["converge_iterations"] = drag.converge.iterations;
      out["converge_stop_reason"] = drag.converge.stop_reason;
      out["converge_tolerance"] = kDragConvergeTolerance;
      out["converge_max_iterations"] = kDragConvergeMaxIterations;

      // What the artist sees: the last frame against the converged shape, and the checkpoints
      // against the shapes their own targets converge to.
      const double diagonal = bounding_box_diagonal(c.mesh);
      const std::vector<Vec3> settled_shape = deformer->vertex_positions();
      SolveOptions refine = base;
      refine.max_iterations = kDragConvergeMaxIterations;
      refine.tolerance = kLagReferenceTolerance;
      const SolveReport refined = deformer->solve(refine);
      const std::vector<Vec3> converged_shape = deformer->vertex_positions();
      const double settle_error = largest_point_distance(converged_shape, settled_shape) / diagonal;
      std::vector<std::pair<const char*, JumpRun>> jumps;
      if (args.undo_redo)
        for (const auto& [name, s] : {std::pair<const char*, double>{"undo", 0.0}, {"redo", 1.0}})
          jumps.emplace_back(name, run_jump(*deformer, c, base, s));
      deformer.reset();
      const double last_distance =
          largest_point_distance(converged_shape, drag.checkpoint_positions.back()) / diagonal;
      std::printf("Lag as the artist sees it: the largest vertex distance to the converged shape, "
                  "%% of the bounding-box diagonal\n");
      std::printf(
          "  last frame against the shape solved on to (relative change %.0e, %d more "
          "iterations; the settle above stopped %.3f%% from it): %.3f%%\n",
          kLagReferenceTolerance, refined.iterations, 100.0 * settle_error, 100.0 * last_distance);
      out["last_frame_max_distance"] = last_distance;
      out["lag_reference_tolerance"] = kLagReferenceTolerance;
      out["lag_reference_iterations"] = refined.iterations;
      out["settle_max_distance_to_reference"] = settle_error;
      std::fflush(stdout);
      const std::vector<LagPoint> lag = measure_lag(c, base, args.frames, drag);
      std::printf("  %6s %12s %16s %8s", "frame", "energy gap %", "max distance %", "ref its");
      if (args.lag_settle) std::printf(" %20s %10s", "to its own settle %", "settle its");
      std::printf("\n");
      nlohmann::json lag_json = nlohmann::json::array();
      for (const LagPoint& p : lag) {
        const double energy_gap = p.converged_energy > 0 ? p.energy / p.converged_energy - 1.0 : 0.0;
        std::printf("  %6d %12.3f %16.3f %8d", p.frame, 100.0 * energy_gap, 100.0 * p.max_distance,
                    p.iterations);
        nlohmann::json point = {{"frame", p.frame},
                                {"energy", p.energy},
                                {"converged_energy", p.converged_energy},
                                {"energy_gap", energy_gap},
                                {"max_distance", p.max_distance},
                                {"reference_iterations", p.iterations}};
        if (p.settle_distance >= 0.0) {
          std::printf(" %20.3f %10d", 100.0 * p.settle_distance, p.settle_iterations);
          point["settle_distance"] = p.settle_distance;
          point["settle_energy"] = p.settle_energy;
          point["settle_iterations"] = p.settle_iterations;
        }
        std::printf("\n");
        lag_json.push_back(point);
      }
      std::printf("\n");
      out["lag"] = lag_json;
      out["lag_every"] = args.lag_every;
      out["lag_settle"] = args.lag_settle;
      if (!jumps.empty()) {
        std::printf("Undo and redo of the drag, solved in the editor's batches (tolerance %.0e)\n",
                    SolveOptions{}.tolerance);
        std::printf("  %6s %8s %8s %10s %10s %8s %14s\n", "", "seconds", "iters", "sub-steps",
                    "their its", "N-K", "energy");
        for (const auto& [name, j] : jumps) {
          std::printf("  %6s %8.3f %8d %10d %10d %8d %14.6e%s\n", name, j.seconds, j.iterations,
                      j.path_steps, j.path_iterations, j.newton_krylov_steps, j.energy,
                      j.converged ? "" : "  (not converged)");
          out[std::string(name)] = {{"seconds", j.seconds},
                                    {"iterations", j.iterations},
                                    {"path_steps", j.path_steps},
                                    {"path_iterations", j.path_iterations},
                                    {"newton_krylov_steps", j.newton_krylov_steps},
                                    {"calls", j.calls},
                                    {"energy", j.energy},
                                    {"converged", j.converged}};
        }
        std::printf("\n");
      }
    }
  }

  const int later = int(drag.frame_seconds.size()) - 1;
  std::printf("Where the time goes (ms; 'coarse' contains the coarse Newton columns after it)\n");
  std::printf("  %-22s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "", "total",
              "targets", "restr+pr", "coarse", "assembly", "factor", "solve", "line srch", "sweeps",
              "accel", "N-Krylov", "vertices", "other");
  print_breakdown_row("first frame", drag.first_frame, method);
  if (later > 0) print_breakdown_row("per frame, 2..N", drag.later_frames.per(later), method);
  if (!args.drag_only) print_breakdown_row("converge (total)", drag.converge_profile, method);
  if (!args.drag_only && drag.converge_profile.newton_krylov_steps > 0)
    std::printf("  (converge: %.0f Newton-Krylov steps, %.0f conjugate-gradient iterations, %.0f "
                "preconditioner applications)\n",
                drag.converge_profile.newton_krylov_steps,
                drag.converge_profile.newton_krylov_iterations,
                drag.converge_profile.newton_krylov_applications);
  std::printf("  (one energy evaluation: %.2f ms)\n", 1e3 * drag.energy_evaluation_seconds);
  std::printf("  (factorizations during the drag: %d in the foreground, %d on a background thread "
              "taking %.0f ms there, not counted above)\n\n",
              drag.foreground_factorizations, drag.background_factorizations,
              1e3 * drag.background_factorization_seconds);
  std::fflush(stdout);
  nlohmann::json profile;
  profile["first_frame_ms"] = drag.first_frame.to_json_ms();
  profile["per_frame_ms"] = drag.later_frames.per(later).to_json_ms();
  profile["per_frame_frames"] = later;
  profile["energy_evaluation_ms"] = 1e3 * drag.energy_evaluation_seconds;
  profile["drag_foreground_factorizations"] = drag.foreground_factorizations;
  profile["drag_background_factorizations"] = drag.background_factorizations;
  profile["drag_background_factorization_ms"] = 1e3 * drag.background_factorization_seconds;
  if (!args.drag_only) profile["converge_ms"] = drag.converge_profile.to_json_ms();

  // 2: the final pose from rest.
  FullSolveRun full;
  if (!args.drag_only) {
    std::printf("Full solve from rest (final targets; relative change %.0e) ...\n",
                kDragConvergeTolerance);
    std::fflush(stdout);
    full = run_full_solve(c, base);
    std::printf("  %8s %9s %9s %9s %6s %12s %14s  %s\n", "setup s", "hier. s", "solve s",
                "to 1% s", "iters", "iters to 1%", "energy", "stop");
    std::printf("  %8.3f %9.3f %9.3f %9.3f %6d %12d %14.6e  %s\n", full.setup_seconds,
                full.hierarchy_build_seconds, full.report.seconds, full.seconds_to_perceived,
                full.report.iterations, full.iterations_to_perceived, full.report.energy,
                full.report.stop_reason.c_str());
    print_breakdown_row("full solve (total)", full.profile, method);
    if (full.profile.newton_krylov_steps > 0)
      std::printf("  (%.0f Newton-Krylov steps, %.0f conjugate-gradient iterations, %.0f "
                  "preconditioner applications)\n",
                  full.profile.newton_krylov_steps, full.profile.newton_krylov_iterations,
                  full.profile.newton_krylov_applications);
    std::printf("\n");
    out["full_solve"] = {{"setup_seconds", full.setup_seconds},
                         {"hierarchy_build_seconds", full.hierarchy_build_seconds},
                         {"seconds", full.report.seconds},
                         {"iterations", full.report.iterations},
                         {"initial_energy", full.report.initial_energy},
                         {"energy", full.report.energy},
                         {"stop_reason", full.report.stop_reason},
                         {"energies", full.report.energies},
                         {"within", kPerceivedGap},
                         {"iterations_to_within", full.iterations_to_perceived},
                         {"seconds_to_within", full.seconds_to_perceived}};
    profile["full_solve_ms"] = full.profile.to_json_ms();
  }
  out["profile"] = profile;

  const double peak = peak_memory_mb();
  std::printf("Peak memory (ru_maxrss)  %.1f MB: after mesh %.1f, after drag %.1f", peak,
              memory_after_mesh, drag.memory_after_drag_mb);
  if (!args.drag_only)
    std::printf(", after converge %.1f, after full solves %.1f", drag.memory_after_converge_mb,
                full.memory_after_mb);
  std::printf("\n\n");
  out["peak_memory_mb"] = peak;
  out["memory_mb"] = {{"after_mesh", memory_after_mesh}, {"after_drag", drag.memory_after_drag_mb}};
  if (!args.drag_only) {
    out["memory_mb"]["after_converge"] = drag.memory_after_converge_mb;
    out["memory_mb"]["after_full_solves"] = full.memory_after_mb;
  }

  const std::vector<double> load_after = load_average();
  const std::string cpu = cpu_model();
  const unsigned threads = std::thread::hardware_concurrency();
  const std::vector<std::string> blas = mapped_blas_libraries();
  std::printf("Machine    %s, %u hardware threads, OPENBLAS_NUM_THREADS=%s\n", cpu.c_str(),
              threads, blas_threads ? blas_threads : "(unset)");
  std::printf("           load average (1 min) before %.2f, after %.2f\n", load_before[0],
              load_after[0]);
  for (const std::string& b : blas) std::printf("           BLAS %s\n", b.c_str());
  std::fflush(stdout);

  out["mesh"] = mesh_path;
  out["faces"] = drag.faces;
  out["vertices"] = drag.vertices;
  out["handles_from"] = c.handles_from;
  out["handles"] = nlohmann::json::array();
  for (const Handle& h : c.handles)
    out["handles"].push_back({{"name", h.name}, {"faces", h.faces.size()}});
  out["forces"] = c.forces.size();
  out["load_seconds"] = c.load_seconds;
  out["subdivide_seconds"] = c.subdivide_seconds;
  out["setup_seconds"] = drag.setup_seconds;
  out["solver_setup_seconds"] = drag.solver_setup_seconds;
  out["hierarchy_bodies"] = drag.level_bodies;
  out["drag_only"] = args.drag_only;
  const char* glibc_tunables = std::getenv("GLIBC_TUNABLES");
  out["machine"] = {{"cpu_model", cpu},
                    {"hardware_threads", threads},
                    {"blas_libraries", blas},
                    {"openblas_num_threads", blas_threads ? blas_threads : ""},
                    {"load_average_before", load_before},
                    {"load_average_after", load_after},
                    // How the allocator was asked for memory: `primo` sets
                    // glibc.malloc.hugetlb=1 (huge pages) unless PRIMO_HUGE_PAGES=0.
                    {"glibc_tunables", glibc_tunables ? glibc_tunables : ""}};
  if (!args.json.empty()) write_text_atomically(args.json, out.dump(2) + "\n");
  return 0;
}

}  // namespace primo::bench
