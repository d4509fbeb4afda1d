#include "engine_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "inputs.h"
#include "machine.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/solve/global_solver.h"
#include "primo/solve/local_solver.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "reach_pose.h"
#include "report.h"

namespace primo::bench {
namespace {

// How big each case is: the full run for docs/performance.md, the quick one for tests.
struct BenchSize {
  int segments;
  int bands;
  double min_seconds;  // of timed work per throughput figure, so timer noise stays small
  int min_iterations;  // of the global throughput run, which is slow per iteration
  int max_iterations;  // of each convergence run
};

constexpr double kCylinderRadius = 0.25;
constexpr double kCylinderHeight = 2.0;
constexpr double kPaperMatchesPerSecond = 67000.0;
constexpr double kPaperUpdatesPerSecond = 6500.0;
constexpr double kConvergenceTolerance = 1e-10;

// ---------------------------------------------------------------------------------------------
// Test cases

// x -> outer(inner(x)).
RigidTransform compose(const RigidTransform& outer, const RigidTransform& inner) {
  RigidTransform t;
  t.rotation = outer.rotation * inner.rotation;
  t.translation = outer.rotation * inner.translation + outer.translation;
  return t;
}

// The limb: a cylinder along y with its bottom band fixed and its top band as the moved handle.
struct CylinderCase {
  Mesh mesh;
  std::vector<int> bottom_band;
  std::vector<int> top_band;
};

CylinderCase make_cylinder_case(const BenchSize& size) {
  CylinderCase c;
  c.mesh =
      make_cylinder(kCylinderRadius, kCylinderHeight, size.segments, size.bands, FaceShape::Quads);
  const FaceGeometry faces = compute_face_geometry(c.mesh);
  const double band_height = kCylinderHeight / size.bands;
  for (int f = 0; f < int(faces.centroid.size()); ++f) {
    const double y = faces.centroid[f].y();
    if (y < band_height)
      c.bottom_band.push_back(f);
    else if (y > kCylinderHeight - band_height)
      c.top_band.push_back(f);
  }
  return c;
}

// The top turned 90 degrees towards +x about the z axis through the top ring centre, and moved
// to where a constant-curvature 90-degree bend of the same length puts it, so the limb keeps
// its length and leans over instead of being stretched or crushed.
RigidTransform bend_90() {
  const Vec3 top_centre(0.0, kCylinderHeight, 0.0);
  const double arc_radius = kCylinderHeight / (M_PI / 2.0);
  const Vec3 bent_top_centre(arc_radius, arc_radius, 0.0);
  return make_rigid_transform(bent_top_centre - top_centre, Vec3::UnitZ(), -90.0, top_centre);
}

// The bend after half a turn about the cylinder's own axis.
RigidTransform bend_90_twist_180() {
  const RigidTransform twist =
      make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), 180.0, Vec3(0.0, kCylinderHeight, 0.0));
  return compose(bend_90(), twist);
}

Deformer make_cylinder_deformer(const CylinderCase& c, const RigidTransform& top_motion) {
  std::vector<Handle> handles = {
      {"bottom", c.bottom_band, Fix::All, RigidTransform::identity()},
      {"top", c.top_band, Fix::All, top_motion},
  };
  return Deformer(c.mesh, PrismParameters{}, std::move(handles));
}

int count_moving_bodies(const RigidSystem& system) {
  int n = 0;
  for (const auto& body : system.bodies)
    if (body.kind != BodyKind::Fixed) ++n;
  return n;
}

// ---------------------------------------------------------------------------------------------
// Measurements

struct LocalThroughput {
  int sweeps = 0;
  long long matches = 0;
  double seconds = 0.0;
  double initial_energy = 0.0;
  double energy = 0.0;
  double per_second() const { return seconds > 0 ? matches / seconds : 0.0; }
};

// `parallel`: the two-thread planned sweep the solvers use; otherwise the plain sequential
// sweep, the paper's single-core figure.
LocalThroughput measure_local(const Deformer& deformer, double min_seconds, bool parallel) {
  const RigidSystem& system = deformer.system();
  std::vector<BodyState> state = deformer.body_states();
  const SweepPlan plan = plan_sweep(system, parallel);
  LocalThroughput result;
  result.initial_energy = system.energy(state);
  const auto start = Clock::now();
  do {
    if (parallel)
      planned_sweep(system, plan, state);
    else
      local_sweep(system, state);
    ++result.sweeps;
  } while (seconds_since(start) < min_seconds);
  result.seconds = seconds_since(start);
  result.matches = (long long)result.sweeps * count_moving_bodies(system);
  result.energy = system.energy(state);
  return result;
}

struct GlobalThroughput {
  int iterations = 0;
  long long updates = 0;
  double seconds = 0.0;
  double analysis_seconds = 0.0;  // symbolic analysis plus the first iteration, not counted
  double per_second() const { return seconds > 0 ? updates / seconds : 0.0; }
};

// Steady-state Gauss-Newton iterations, as the paper counts them (its symbolic factorization
// is precomputed): a one-iteration solve makes the deformer analyse the pattern, reset() keeps
// that analysis, and only the iterations after it are timed.
GlobalThroughput measure_global(Deformer& deformer, double min_seconds, int min_iterations) {
  GlobalThroughput result;
  SolveOptions warm_up;
  warm_up.method = SolveMethod::Global;
  warm_up.max_iterations = 1;
  warm_up.path.enabled = false;  // the paper's one-step iterations (see run_convergence)
  result.analysis_seconds = deformer.solve(warm_up).seconds;
  deformer.reset();

  SolveOptions chunk;
  chunk.method = SolveMethod::Global;
  chunk.max_iterations = 5;
  chunk.tolerance = 0.0;  // a fixed amount of work, not a converged answer
  chunk.exact_hessian_below = 0.0;
  chunk.path.enabled = false;
  while (result.seconds < min_seconds || result.iterations < min_iterations) {
    const SolveReport report = deformer.solve(chunk);
    if (report.iterations == 0) break;  // nothing to solve even from rest: no figure
    result.iterations += report.iterations;
    result.seconds += report.seconds;
    if (report.converged) deformer.reset();  // at the minimum: start over for more work
  }
  result.updates = (long long)result.iterations * count_moving_bodies(deformer.system());
  return result;
}

struct ConvergenceRun {
  std::string deformation;
  std::string hessian;
  SolveReport report;
};

ConvergenceRun run_convergence(const CylinderCase& c, const std::string& deformation,
                               const RigidTransform& top_motion, bool exact_hessian,
                               int max_iterations) {
  Deformer deformer = make_cylinder_deformer(c, top_motion);
  SolveOptions options;
  options.method = SolveMethod::Global;
  options.max_iterations = max_iterations;
  options.tolerance = kConvergenceTolerance;
  if (!exact_hessian) options.exact_hessian_below = 0.0;
  // The paper counts Newton iterations of one large step; `primo deform` would first follow
  // the edit in sub-steps (docs/engine.md, "Large steps"), which these counts leave out.
  options.path.enabled = false;
  return {deformation, exact_hessian ? "exact near min" : "Gauss-Newton", deformer.solve(options)};
}

// The lowest final energy any run reached for this deformation: the reference for "close".
double lowest_energy(const std::vector<ConvergenceRun>& runs, const std::string& deformation) {
  double lowest = INFINITY;
  for (const ConvergenceRun& run : runs)
    if (run.deformation == deformation) lowest = std::min(lowest, run.report.energy);
  return lowest;
}

// How many iterations it took to get within `relative` of `best` (the paper's "< 10
// iterations" is about visible convergence, not 1e-10), or -1 when it never did.
int iterations_to_within(const SolveReport& report, double best, double relative) {
  for (size_t k = 0; k < report.energies.size(); ++k)
    if (report.energies[k] - best <= relative * best) return int(k) + 1;
  return -1;
}

std::string count_or_dash(int count) { return count < 0 ? "-" : std::to_string(count); }

struct RealMeshRun {
  std::string path;
  int faces = 0;
  int vertices = 0;
  int moving_bodies = 0;
  double load_seconds = 0.0;
  double setup_seconds = 0.0;
  double analysis_seconds = 0.0;
  SolveReport report;
  double updates_per_second() const {
    return report.seconds > 0 ? double(report.iterations) * moving_bodies / report.seconds : 0.0;
  }
  // Without the one-time symbolic analysis, comparable with the steady-state cylinder figure.
  double iteration_updates_per_second() const {
    const double t = report.seconds - analysis_seconds;
    return t > 0 ? double(report.iterations) * moving_bodies / t : 0.0;
  }
};

RealMeshRun run_real_mesh(const std::string& path) {
  RealMeshRun run;
  run.path = path;
  auto start = Clock::now();
  const Mesh mesh = load_mesh(path);
  run.load_seconds = seconds_since(start);
  run.faces = int(mesh.n_faces());
  run.vertices = int(mesh.n_vertices());
  std::vector<Handle> handles = make_reach_pose(mesh, path).handles();

  start = Clock::now();
  Deformer deformer(mesh, PrismParameters{}, std::move(handles));
  run.setup_seconds = seconds_since(start);
  run.moving_bodies = count_moving_bodies(deformer.system());

  // The solve below analyses the pattern again inside the deformer; timing a separate analysis
  // of the same system tells how much of the solve time is that one-time cost.
  start = Clock::now();
  { GlobalSolver analysis_only(deformer.system()); }
  run.analysis_seconds = seconds_since(start);

  SolveOptions options;  // the scenario format's defaults, in one step as the paper counts
  options.method = SolveMethod::Global;
  options.path.enabled = false;
  run.report = deformer.solve(options);
  return run;
}

}  // namespace

int run_engine_bench(const EngineBenchOptions& args) {
  std::error_code ec;  // fail before minutes of measuring rather than after them
  if (!args.mesh.empty() && !std::filesystem::is_regular_file(args.mesh, ec))
    throw Error(args.mesh + ": no such mesh file");
  check_json_folder(args.json);
  const BenchSize size =
      args.quick ? BenchSize{20, 30, 0.05, 3, 60} : BenchSize{40, 60, 0.5, 10, 500};
  nlohmann::json out;
  out["quick"] = args.quick;
  const std::string build = build_label();
  out["build"] = build;

  const CylinderCase cylinder = make_cylinder_case(size);
  Deformer bent = make_cylinder_deformer(cylinder, bend_90());
  const int moving = count_moving_bodies(bent.system());
  out["cylinder"] = {{"radius", kCylinderRadius},
                     {"height", kCylinderHeight},
                     {"segments", size.segments},
                     {"bands", size.bands},
                     {"faces", int(cylinder.mesh.n_faces())},
                     {"moving_bodies", moving}};

  std::printf("primo bench engine%s  [build: %s]\n\n", args.quick ? " --quick" : "", build.c_str());
  std::printf(
      "Cylinder r %.2f, height %.1f, %d x %d = %d quads; bottom and top bands fixed, "
      "%d moving prisms\n\n",
      kCylinderRadius, kCylinderHeight, size.segments, size.bands, int(cylinder.mesh.n_faces()),
      moving);
  std::fflush(stdout);

  // 1, 2: throughput on the 90-degree bend.
  const LocalThroughput local = measure_local(bent, size.min_seconds, false);
  const LocalThroughput local_parallel = measure_local(bent, size.min_seconds, true);
  const GlobalThroughput global = measure_global(bent, size.min_seconds, size.min_iterations);
  out["local"] = {{"sweeps", local.sweeps},
                  {"matches", local.matches},
                  {"seconds", local.seconds},
                  {"matches_per_second", local.per_second()},
                  {"initial_energy", local.initial_energy},
                  {"energy_after_sweeps", local.energy},
                  {"paper_matches_per_second", kPaperMatchesPerSecond},
                  {"two_thread_sweeps", local_parallel.sweeps},
                  {"two_thread_matches_per_second", local_parallel.per_second()}};
  out["global"] = {{"iterations", global.iterations},
                   {"updates", global.updates},
                   {"seconds", global.seconds},
                   {"updates_per_second", global.per_second()},
                   {"analysis_and_first_iteration_seconds", global.analysis_seconds},
                   {"paper_updates_per_second", kPaperUpdatesPerSecond}};

  std::printf("Throughput (90-degree bend)       %10s %10s %9s %14s %14s\n", "runs", "count",
              "seconds", "per second", "paper P4 3.2G");
  std::printf("  local matches, sequential sweep %10d %10s %9.3f %14s %14s\n", local.sweeps,
              with_thousands(double(local.matches)).c_str(), local.seconds,
              with_thousands(local.per_second()).c_str(),
              with_thousands(kPaperMatchesPerSecond).c_str());
  std::printf("  local matches, 2-thread sweep   %10d %10s %9.3f %14s %14s\n",
              local_parallel.sweeps, with_thousands(double(local_parallel.matches)).c_str(),
              local_parallel.seconds, with_thousands(local_parallel.per_second()).c_str(), "");
  std::printf("  global prism updates, GN        %10d %10s %9.3f %14s %14s\n", global.iterations,
              with_thousands(double(global.updates)).c_str(), global.seconds,
              with_thousands(global.per_second()).c_str(),
              with_thousands(kPaperUpdatesPerSecond).c_str());
  std::printf("  (global: symbolic analysis + first iteration %.3f s, not counted)\n\n",
              global.analysis_seconds);
  std::fflush(stdout);

  // 3: iterations to a relative energy change of 1e-10.
  std::vector<ConvergenceRun> runs;
  for (bool exact : {false, true})
    runs.push_back(run_convergence(cylinder, "bend 90", bend_90(), exact, size.max_iterations));
  for (bool exact : {false, true})
    runs.push_back(run_convergence(cylinder, "bend 90 + twist 180", bend_90_twist_180(), exact,
                                   size.max_iterations));
  std::printf("Global solve to relative energy change %.0e (max %d iterations)\n",
              kConvergenceTolerance, size.max_iterations);
  std::printf("  %-20s %-15s %6s %6s %6s %6s %13s %13s %9s  %s\n", "deformation", "hessian",
              "iters", "exact", "<1e-3", "<1e-6", "start energy", "final energy", "seconds",
              "stop");
  out["convergence_tolerance"] = kConvergenceTolerance;
  out["convergence_max_iterations"] = size.max_iterations;
  out["convergence"] = nlohmann::json::array();
  for (const ConvergenceRun& run : runs) {
    const SolveReport& r = run.report;
    const double best = lowest_energy(runs, run.deformation);
    const int to_1e3 = iterations_to_within(r, best, 1e-3);
    const int to_1e6 = iterations_to_within(r, best, 1e-6);
    std::printf("  %-20s %-15s %6d %6d %6s %6s %13.6e %13.6e %9.3f  %s\n", run.deformation.c_str(),
                run.hessian.c_str(), r.iterations, r.exact_newton_steps,
                count_or_dash(to_1e3).c_str(), count_or_dash(to_1e6).c_str(), r.initial_energy,
                r.energy, r.seconds, r.stop_reason.c_str());
    nlohmann::json j = report_json(r);
    j["deformation"] = run.deformation;
    j["hessian"] = run.hessian;
    j["iterations_to_within_1e-3_of_best"] = to_1e3;
    j["iterations_to_within_1e-6_of_best"] = to_1e6;
    j["energies"] = r.energies;
    out["convergence"].push_back(j);
  }
  std::printf("  (seconds include the one-time symbolic analysis)\n\n");
  std::fflush(stdout);

  // 4: a real mesh.
  std::string mesh_path = args.mesh;
  std::string skipped;
  if (mesh_path.empty()) {
    if (args.quick)
      skipped = "skipped: --quick (pass --mesh to run it anyway)";
    else if ((mesh_path = find_shared_mesh(kEngineBenchMesh)).empty())
      skipped = std::string("skipped: ") + kEngineBenchMesh + " not found (pass --mesh)";
  }
  std::printf(
      "Real mesh: global solve, bottom 10%% fixed, top 10%% turned 30 deg about x and "
      "moved 10%% of the diagonal along +z\n");
  if (!skipped.empty()) {
    std::printf("  %s\n\n", skipped.c_str());
    out["real_mesh"] = {{"skipped", skipped}};
  } else {
    const RealMeshRun run = run_real_mesh(mesh_path);
    const SolveReport& r = run.report;
    std::printf("  %s\n", run.path.c_str());
    std::printf("  %8s %7s %7s %8s %9s %6s %6s %13s %12s %12s  %s\n", "faces", "load s", "setup s",
                "analys s", "solve s", "iters", "exact", "final energy", "updates/s", "excl. anal.",
                "stop");
    std::printf("  %8d %7.3f %7.3f %8.3f %9.3f %6d %6d %13.6e %12s %12s  %s\n\n", run.faces,
                run.load_seconds, run.setup_seconds, run.analysis_seconds, r.seconds, r.iterations,
                r.exact_newton_steps, r.energy, with_thousands(run.updates_per_second()).c_str(),
                with_thousands(run.iteration_updates_per_second()).c_str(), r.stop_reason.c_str());
    nlohmann::json j = report_json(r);
    j["path"] = run.path;
    j["faces"] = run.faces;
    j["vertices"] = run.vertices;
    j["moving_bodies"] = run.moving_bodies;
    j["load_seconds"] = run.load_seconds;
    j["setup_seconds"] = run.setup_seconds;
    j["analysis_seconds"] = run.analysis_seconds;
    j["updates_per_second"] = run.updates_per_second();
    j["updates_per_second_excluding_analysis"] = run.iteration_updates_per_second();
    out["real_mesh"] = j;
  }

  // 5: the machine, last, because the BLAS is only mapped once CHOLMOD has factorized.
  const unsigned threads = std::thread::hardware_concurrency();
  const std::string cpu = cpu_model();
  const std::vector<std::string> blas = mapped_blas_libraries();
  out["machine"] = {{"hardware_threads", threads}, {"cpu_model", cpu}, {"blas_libraries", blas}};
  std::printf("Machine\n");
  std::printf("  CPU               %s\n", cpu.c_str());
  std::printf("  hardware threads  %u\n", threads);
  if (blas.empty()) std::printf("  BLAS (CHOLMOD)    none mapped\n");
  for (size_t i = 0; i < blas.size(); ++i)
    std::printf("  %-17s %s\n", i == 0 ? "BLAS (CHOLMOD)" : "", blas[i].c_str());
  std::fflush(stdout);

  if (!args.json.empty()) write_text_atomically(args.json, out.dump(2) + "\n");
  return 0;
}

}  // namespace primo::bench
