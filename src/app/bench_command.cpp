// `primo bench engine [--mesh PATH] [--json FILE] [--quick]`
// `primo bench drag SCENARIO.json [--frames N] [--solver S] [--json FILE] [--mesh MESH]
//                   [--subdivide K] [--bbox-handles]` (below, after the engine benchmark)
//
// Measures the engine against the figures the paper quotes (Sect. 4: 67k local matches/s and
// 6,500 global prism updates/s on a 3.2 GHz Pentium 4; < 10 global iterations even for extreme
// deformations): local and global throughput and Newton iteration counts on a limb-like
// cylinder, and a global solve of a ~30k-face real mesh. Prints a table; --json writes the same
// figures. `bench` is a group, so `bench drag` sits beside `engine`, and `bench quality`
// (quality_bench.cpp) beside both.

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "commands.h"
#include "primo/output_files.h"
#include "primo/scenario_solve.h"
#include "shared_meshes.h"
#include "primo/deformer.h"
#include "primo/error.h"
#include "primo/geometry.h"
#include "primo/global_solver.h"
#include "primo/hierarchical_solver.h"
#include "primo/local_solver.h"
#include "primo/mesh_generators.h"
#include "primo/mesh_io.h"
#include "primo/mesh_subdivision.h"
#include "primo/scenario.h"

namespace fs = std::filesystem;

namespace primo::app {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct BenchEngineArguments {
  std::string mesh;
  std::string json;
  bool quick = false;
};

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
const char* const kDefaultMeshName = "armadillo_29k.obj";

// ---------------------------------------------------------------------------------------------
// Machine description

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t begin = line.find_first_not_of(" \t", colon + 1);
    return begin == std::string::npos ? "unknown" : line.substr(begin);
  }
  return "unknown";
}

// CHOLMOD loads its BLAS dynamically through the system's alternatives, so the only cheap way
// to tell which one runs is to look at what is mapped into the process after a solve.
std::vector<std::string> mapped_blas_libraries() {
  std::ifstream maps("/proc/self/maps");
  std::set<std::string> found;
  std::string line;
  while (std::getline(maps, line)) {
    const size_t slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    const std::string name = fs::path(path).filename().string();
    if (name.find("blas") != std::string::npos || name.find("lapack") != std::string::npos ||
        name.find("mkl") != std::string::npos)
      found.insert(path);
  }
  return {found.begin(), found.end()};
}

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

// Bottom tenth (in y) fixed; top tenth turned 30 degrees about x through its centroid and
// pushed along +z by a tenth of the bounding-box diagonal: a reach-forward pose. Any mesh.
struct ReachPose {
  std::vector<int> bottom;
  std::vector<int> top;
  Vec3 top_centroid = Vec3::Zero();
  Vec3 translate = Vec3::Zero();
  Vec3 axis = Vec3::UnitX();
  double angle_deg = 30.0;

  RigidTransform top_motion() const {
    return make_rigid_transform(translate, axis, angle_deg, top_centroid);
  }
  std::vector<Handle> handles() const {
    return {{"bottom", bottom, Fix::All, RigidTransform::identity()},
            {"top", top, Fix::All, top_motion()}};
  }
};

ReachPose make_reach_pose(const Mesh& mesh, const std::string& source) {
  const FaceGeometry faces = compute_face_geometry(mesh);
  double y_min = INFINITY, y_max = -INFINITY;
  for (auto v : mesh.vertices()) {
    y_min = std::min(y_min, mesh.point(v).y());
    y_max = std::max(y_max, mesh.point(v).y());
  }
  const double y_extent = y_max - y_min;
  ReachPose pose;
  for (int f = 0; f < int(mesh.n_faces()); ++f) {
    const double y = faces.centroid[f].y();
    if (y < y_min + 0.1 * y_extent)
      pose.bottom.push_back(f);
    else if (y > y_max - 0.1 * y_extent)
      pose.top.push_back(f);
  }
  if (pose.bottom.empty() || pose.top.empty())
    throw Error(source + ": no faces in the bottom or top tenth of the bounding box");
  pose.top_centroid = area_weighted_centroid(faces, pose.top);
  pose.translate = Vec3(0.0, 0.0, 0.1 * bounding_box_diagonal(mesh));
  return pose;
}

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

// ---------------------------------------------------------------------------------------------
// Output

std::string with_thousands(double value) {
  const long long n = std::llround(value);
  std::string digits = std::to_string(n < 0 ? -n : n);
  for (int i = int(digits.size()) - 3; i > 0; i -= 3) digits.insert(size_t(i), ",");
  return (n < 0 ? "-" : "") + digits;
}

nlohmann::json report_json(const SolveReport& r) {
  return {{"iterations", r.iterations},
          {"exact_newton_steps", r.exact_newton_steps},
          {"initial_energy", r.initial_energy},
          {"energy", r.energy},
          {"seconds", r.seconds},
          {"converged", r.converged},
          {"stop_reason", r.stop_reason}};
}

// Fails before minutes of measuring rather than after them.
void check_arguments(const BenchEngineArguments& args) {
  std::error_code ec;
  if (!args.mesh.empty() && !fs::is_regular_file(args.mesh, ec))
    throw Error(args.mesh + ": no such mesh file");
  if (!args.json.empty()) {
    const fs::path folder = fs::absolute(fs::path(args.json)).parent_path();
    if (!fs::is_directory(folder, ec))
      throw Error(args.json + ": the folder " + folder.string() + " does not exist");
  }
}

int run_bench_engine(const BenchEngineArguments& args) {
  check_arguments(args);
  const BenchSize size =
      args.quick ? BenchSize{20, 30, 0.05, 3, 60} : BenchSize{40, 60, 0.5, 10, 500};
  nlohmann::json out;
  out["quick"] = args.quick;
#ifdef NDEBUG
  const char* build = "optimized (NDEBUG)";
#else
  const char* build = "debug (assertions on): figures are not representative";
#endif
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

  std::printf("primo bench engine%s  [build: %s]\n\n", args.quick ? " --quick" : "", build);
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
    else if ((mesh_path = find_shared_mesh(kDefaultMeshName)).empty())
      skipped = std::string("skipped: ") + kDefaultMeshName + " not found (pass --mesh)";
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

// =============================================================================================
// `primo bench drag SCENARIO.json [--frames N] [--solver S] [--json FILE] [--mesh MESH]
//                   [--subdivide K] [--bbox-handles]`
//
// An interactive drag: every handle goes from rest to its scenario transform in N equal steps,
// with one solver iteration (one hierarchical cycle, one global Newton iteration or one local
// sweep) and one read of the vertex positions per frame, as the editor does while a handle is
// dragged. Then the solve continues to convergence, and a fresh deformer solves the final pose
// from rest. docs/performance.md describes every figure.

struct BenchDragArguments {
  std::string scenario;
  int frames = 60;
  std::string solver = "hierarchical";
  std::string json;
  std::string mesh;
  int subdivide = 0;
  bool bbox_handles = false;
  bool drag_only = false;  // no convergence afterwards, no full solve: for repeated timings
  HierarchicalOptions hierarchical;  // the core's defaults unless the experiment flags say otherwise
};

constexpr double kDragConvergeTolerance = 1e-7;
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
                        const BenchDragArguments& args) {
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

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux: KiB
}

std::vector<double> load_average() {
  std::ifstream in("/proc/loadavg");
  std::vector<double> load(3, -1.0);
  for (double& l : load) in >> l;
  return load;
}

// The solvers' accumulated phase timings at one moment; differences give a phase's share.
struct SolverClock {
  double restrict_prolong = 0.0;
  double coarse = 0.0;
  double sweeps = 0.0;
  double acceleration = 0.0;
  int cycles = 0;
  GlobalSolverTimings newton;  // the coarse level's solver (hierarchical) or the global solver

  static SolverClock read(const Deformer& deformer) {
    SolverClock c;
    if (const HierarchicalSolver* h = deformer.hierarchical_solver()) {
      c.restrict_prolong = h->timings().restrict_prolong;
      c.coarse = h->timings().coarse;
      c.sweeps = h->timings().sweeps;
      c.acceleration = h->timings().acceleration;
      c.cycles = h->timings().cycles;
      if (const GlobalSolver* g = h->coarse_solver()) c.newton = g->timings();
    } else if (const GlobalSolver* g = deformer.global_solver()) {
      c.newton = g->timings();
    }
    return c;
  }
};

// Where the wall time of a phase went, in seconds. `other` is what no solver timer covers:
// energy evaluations in Deformer::solve and after each cycle, local sweeps of the Local
// method, building the hierarchy or the global solver's analysis on first use.
struct Breakdown {
  double total = 0.0;
  double set_targets = 0.0;
  double restrict_prolong = 0.0;
  double coarse = 0.0;
  double assembly = 0.0;
  double factorization = 0.0;
  double solve = 0.0;
  double line_search = 0.0;
  double sweeps = 0.0;
  double acceleration = 0.0;  // Anderson proposals and their energy
  double vertex_update = 0.0;
  double factorizations = 0.0;  // count (per frame after per())

  double newton() const { return assembly + factorization + solve + line_search; }
  double other() const {
    // The coarse phase contains the coarse Newton parts; the global method has no coarse phase.
    const double solver = restrict_prolong + sweeps + acceleration + std::max(coarse, newton());
    return total - set_targets - vertex_update - solver;
  }
  void add_solver(const SolverClock& before, const SolverClock& after) {
    restrict_prolong += after.restrict_prolong - before.restrict_prolong;
    coarse += after.coarse - before.coarse;
    sweeps += after.sweeps - before.sweeps;
    acceleration += after.acceleration - before.acceleration;
    assembly += after.newton.assembly - before.newton.assembly;
    factorization += after.newton.factorization - before.newton.factorization;
    solve += after.newton.solve - before.newton.solve;
    line_search += after.newton.line_search - before.newton.line_search;
    factorizations += after.newton.factorizations - before.newton.factorizations;
  }
  Breakdown per(int n) const {
    Breakdown b = *this;
    const double k = n > 0 ? 1.0 / n : 0.0;
    for (double* x : {&b.total, &b.set_targets, &b.restrict_prolong, &b.coarse, &b.assembly,
                      &b.factorization, &b.solve, &b.line_search, &b.sweeps, &b.acceleration,
                      &b.vertex_update, &b.factorizations})
      *x *= k;
    return b;
  }
  nlohmann::json to_json_ms() const {
    return {{"total", 1e3 * total},
            {"set_targets", 1e3 * set_targets},
            {"restrict_prolong", 1e3 * restrict_prolong},
            {"coarse", 1e3 * coarse},
            {"assembly", 1e3 * assembly},
            {"factorization", 1e3 * factorization},
            {"solve", 1e3 * solve},
            {"line_search", 1e3 * line_search},
            {"sweeps", 1e3 * sweeps},
            {"acceleration", 1e3 * acceleration},
            {"vertex_update", 1e3 * vertex_update},
            {"other", 1e3 * other()},
            {"factorizations", factorizations}};
  }
};

struct DragRun {
  int faces = 0;
  int vertices = 0;
  double setup_seconds = 0.0;  // Deformer construction
  double solver_setup_seconds = 0.0;  // Deformer::prepare: hierarchy, symbolic analysis
  std::vector<double> frame_seconds;
  std::vector<double> frame_energies;
  Breakdown first_frame;
  Breakdown later_frames;  // sum over frames 2..N
  double energy_evaluation_seconds = 0.0;
  int drag_factor_lag = 0;  // steps of the background refreshes during the drag
  int foreground_factorizations = 0, background_factorizations = 0;  // during the drag
  double background_factorization_seconds = 0.0;
  std::vector<int> level_bodies;  // hierarchical: bodies per level, fine first
  SolveReport converge;
  Breakdown converge_profile;
  double memory_after_drag_mb = 0.0;
  double memory_after_converge_mb = 0.0;
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

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void set_targets(Deformer& deformer, const DragCase& c, double s) {
  for (size_t i = 0; i < c.paths.size(); ++i) deformer.set_handle_transform(int(i), c.paths[i].at(s));
  for (size_t j = 0; j < c.forces.size(); ++j)
    deformer.set_force_offset(int(j), s * c.forces[j].target_offset);
}

double g_sink = 0.0;  // keeps the vertex read from being optimized away

// The drag on `deformer` (made with the final targets): targets back to rest, then N frames.
void run_frames(Deformer& deformer, const DragCase& c, const SolveOptions& base, int frames,
                DragRun& run) {
  set_targets(deformer, c, 0.0);  // every handle and force back at rest
  deformer.reset();
  // The editor sets the solver up when the handles are made, before they are dragged.
  const auto setup_start = Clock::now();
  deformer.prepare(base);
  run.solver_setup_seconds = seconds_since(setup_start);
  const SolverClock after_setup = SolverClock::read(deformer);

  SolveOptions frame = base;
  frame.max_iterations = 1;
  frame.tolerance = 0.0;
  for (int k = 1; k <= frames; ++k) {
    const SolverClock before = SolverClock::read(deformer);
    const auto t0 = Clock::now();
    set_targets(deformer, c, double(k) / frames);
    const auto t1 = Clock::now();
    const SolveReport report = deformer.solve(frame);
    const auto t2 = Clock::now();
    const std::vector<Vec3> positions = deformer.vertex_positions();
    const auto t3 = Clock::now();
    g_sink += positions.empty() ? 0.0 : positions.back().x();

    Breakdown& b = k == 1 ? run.first_frame : run.later_frames;
    b.total += std::chrono::duration<double>(t3 - t0).count();
    b.set_targets += std::chrono::duration<double>(t1 - t0).count();
    b.vertex_update += std::chrono::duration<double>(t3 - t2).count();
    b.add_solver(before, SolverClock::read(deformer));
    run.frame_seconds.push_back(std::chrono::duration<double>(t3 - t0).count());
    run.frame_energies.push_back(report.energy);
  }
  if (const HierarchicalSolver* h = deformer.hierarchical_solver()) {
    for (int l = 0; l < h->levels(); ++l) run.level_bodies.push_back(h->bodies(l));
    run.drag_factor_lag = h->drag_factor_lag();
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

// --- Reporting ----------------------------------------------------------------------------------

void print_breakdown_row(const char* label, const Breakdown& b, SolveMethod method) {
  std::printf("  %-22s %9.2f %8.2f %8.2f", label, 1e3 * b.total, 1e3 * b.set_targets,
              1e3 * b.restrict_prolong);
  if (method == SolveMethod::Hierarchical)
    std::printf(" %8.2f", 1e3 * b.coarse);
  else
    std::printf(" %8s", "-");
  std::printf(" %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f\n", 1e3 * b.assembly,
              1e3 * b.factorization, 1e3 * b.solve, 1e3 * b.line_search, 1e3 * b.sweeps,
              1e3 * b.acceleration, 1e3 * b.vertex_update, 1e3 * b.other());
}

void check_drag_arguments(const BenchDragArguments& args) {
  std::error_code ec;
  if (!args.json.empty()) {
    const fs::path folder = fs::absolute(fs::path(args.json)).parent_path();
    if (!fs::is_directory(folder, ec))
      throw Error(args.json + ": the folder " + folder.string() + " does not exist");
  }
}

int run_bench_drag(const BenchDragArguments& args) {
  check_drag_arguments(args);
  const Scenario scenario = load_scenario(args.scenario);
  const SolveMethod method = drag_method(args.solver);
#ifdef NDEBUG
  const char* build = "optimized (NDEBUG)";
#else
  const char* build = "debug (assertions on): figures are not representative";
#endif
  const std::vector<double> load_before = load_average();
  const char* blas_threads = std::getenv("OPENBLAS_NUM_THREADS");

  nlohmann::json out;
  out["scenario"] = args.scenario;
  out["build"] = build;
  out["solver"] = solve_method_name(method);
  out["frames"] = args.frames;
  out["subdivide"] = args.subdivide;
  out["bbox_handles"] = args.bbox_handles;
  std::printf("primo bench drag %s  [build: %s]\n\n", args.scenario.c_str(), build);

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
  std::printf(": %d faces, %d vertices (load %.2f s", int(c.mesh.n_faces()),
              int(c.mesh.n_vertices()), c.load_seconds);
  if (args.subdivide > 0) std::printf(", subdivide %.2f s", c.subdivide_seconds);
  std::printf(")\n");
  std::printf("Handles    from the %s:", c.handles_from.c_str());
  for (const Handle& h : c.handles)
    std::printf(" %s (%zu faces)", h.name.empty() ? "-" : h.name.c_str(), h.faces.size());
  std::printf("; %zu forces\n", c.forces.size());
  std::printf("Solver     %s, %d frames of one iteration each%s\n", solve_method_name(method),
              args.frames, args.drag_only ? " (--drag-only)" : "");
  SolveOptions base;
  base.method = method;
  base.hierarchical = args.hierarchical;
  // The full solve from rest is the one-step solve the drag's figures have always been
  // compared with (docs/performance.md); a drag's frames are small steps either way.
  base.path.enabled = false;
  const HierarchicalOptions defaults;
  const bool tuned = args.hierarchical.hierarchy.coarsest_max_bodies !=
                         defaults.hierarchy.coarsest_max_bodies ||
                     args.hierarchical.hierarchy.cluster_size != defaults.hierarchy.cluster_size ||
                     args.hierarchical.sweeps_per_level != defaults.sweeps_per_level ||
                     args.hierarchical.intermediate_sweeps != defaults.intermediate_sweeps ||
                     args.hierarchical.coarse_iterations != defaults.coarse_iterations ||
                     args.hierarchical.intermediate_cycles != defaults.intermediate_cycles ||
                     args.hierarchical.coarse_factor_reuse != defaults.coarse_factor_reuse ||
                     args.hierarchical.drag_factor_reuse != defaults.drag_factor_reuse ||
                     args.hierarchical.drag_factor_lag != defaults.drag_factor_lag ||
                     args.hierarchical.intermediate_relaxation != defaults.intermediate_relaxation ||
                     args.hierarchical.acceleration_history != defaults.acceleration_history;
  const nlohmann::json settings = {
      {"cluster_size", args.hierarchical.hierarchy.cluster_size},
      {"coarsest_max_bodies", args.hierarchical.hierarchy.coarsest_max_bodies},
      {"fine_sweeps", args.hierarchical.sweeps_per_level},
      {"intermediate_sweeps", args.hierarchical.intermediate_sweeps},
      {"coarse_iterations", args.hierarchical.coarse_iterations},
      {"intermediate_cycles", args.hierarchical.intermediate_cycles},
      {"coarse_factor_reuse", args.hierarchical.coarse_factor_reuse},
      {"drag_factor_reuse", args.hierarchical.drag_factor_reuse},
      {"drag_factor_lag", args.hierarchical.drag_factor_lag},
      {"intermediate_relaxation", args.hierarchical.intermediate_relaxation},
      {"acceleration_history", args.hierarchical.acceleration_history},
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
                "coarse factorization reused up to %d times%s%s\n",
                args.hierarchical.hierarchy.cluster_size,
                args.hierarchical.hierarchy.coarsest_max_bodies,
                args.hierarchical.sweeps_per_level, args.hierarchical.intermediate_sweeps,
                args.hierarchical.intermediate_cycles, args.hierarchical.coarse_iterations,
                args.hierarchical.coarse_factor_reuse, drag_refresh.c_str(),
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
    Deformer deformer(c.mesh, c.prisms, c.handles, c.forces);
    drag.setup_seconds = seconds_since(start);
    run_frames(deformer, c, base, args.frames, drag);

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
      std::printf("\n\n");
      out["drag_factor_lag"] = drag.drag_factor_lag;
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
    out["max_ms"] = max_ms;
    out["first_frame_ms"] = 1e3 * drag.frame_seconds.front();
    out["max_ms_after_first"] = max_later_ms;
    out["final_energy"] = drag.frame_energies.back();

    if (!args.drag_only) {
      run_converge(deformer, base, drag);
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
    }
  }

  const int later = int(drag.frame_seconds.size()) - 1;
  std::printf("Where the time goes (ms; 'coarse' contains the coarse Newton columns after it)\n");
  std::printf("  %-22s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "", "total",
              "targets", "restr+pr", "coarse", "assembly", "factor", "solve", "line srch",
              "sweeps", "accel", "vertices", "other");
  print_breakdown_row("first frame", drag.first_frame, method);
  if (later > 0) print_breakdown_row("per frame, 2..N", drag.later_frames.per(later), method);
  if (!args.drag_only) print_breakdown_row("converge (total)", drag.converge_profile, method);
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
  out["machine"] = {{"cpu_model", cpu},
                    {"hardware_threads", threads},
                    {"blas_libraries", blas},
                    {"openblas_num_threads", blas_threads ? blas_threads : ""},
                    {"load_average_before", load_before},
                    {"load_average_after", load_after}};
  if (!args.json.empty()) write_text_atomically(args.json, out.dump(2) + "\n");
  return 0;
}

}  // namespace

Command register_bench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Measure the engine's speed and convergence");
  bench->require_subcommand(1);

  auto engine_args = std::make_shared<BenchEngineArguments>();
  CLI::App* engine = bench->add_subcommand(
      "engine", "Local/global throughput and iteration counts (cylinder), and a real-mesh solve");
  engine->add_option("--mesh", engine_args->mesh,
                     std::string("Real mesh for the large solve (default: shared/meshes/") +
                         kDefaultMeshName + ", searched upward from the working directory)");
  engine->add_option("--json", engine_args->json, "Also write the figures as JSON");
  engine->add_flag("--quick", engine_args->quick,
                   "Small cases only (600-face cylinder, no real mesh unless --mesh): seconds");

  auto drag_args = std::make_shared<BenchDragArguments>();
  CLI::App* drag = bench->add_subcommand(
      "drag", "Interactive drag: one solver iteration per frame, then on to convergence");
  drag->add_option("scenario", drag_args->scenario, "Scenario file (primo-scenario/1 JSON)")
      ->required();
  drag->add_option("--frames", drag_args->frames, "Frames from rest to the targets (default 60)")
      ->check(CLI::Range(1, 100000));
  drag->add_option("--solver", drag_args->solver,
                   "hierarchical (default), global or local; one iteration per frame")
      ->check(CLI::IsMember({"hierarchical", "global", "local"}));
  drag->add_option("--json", drag_args->json, "Also write the figures as JSON");
  drag->add_option("--mesh", drag_args->mesh,
                   "Use this mesh instead of the scenario's (a bare file name is also looked up "
                   "in shared/meshes above the working directory)");
  drag->add_option("--subdivide", drag_args->subdivide,
                   "Loop-subdivide the (triangle) mesh this many times first")
      ->check(CLI::Range(0, 4));
  drag->add_flag("--bbox-handles", drag_args->bbox_handles,
                 "Ignore the scenario's regions, handles and forces: bottom tenth (y) fixed, top "
                 "tenth turned 30 deg about x and moved a tenth of the diagonal along +z");
  drag->add_flag("--drag-only", drag_args->drag_only,
                 "Only the frames: no solving on to convergence, no full solve from rest");
  // Experiments with the hierarchical solver's settings (SolveOptions::hierarchical); the
  // defaults are the core's, which the editor and `primo deform` use.
  HierarchicalOptions& h = drag_args->hierarchical;
  const char* group = "Hierarchical solver settings (experiments; default: the core's)";
  drag->add_option("--cluster-size", h.hierarchy.cluster_size, "Bodies per cluster")
      ->check(CLI::Range(2, 1000))
      ->group(group);
  drag->add_option("--coarsest-max-bodies", h.hierarchy.coarsest_max_bodies,
                   "Coarsen until the coarsest level has at most this many bodies")
      ->check(CLI::Range(1, 10000000))
      ->group(group);
  drag->add_option("--fine-sweeps", h.sweeps_per_level, "Local sweeps on the fine level per cycle")
      ->check(CLI::Range(0, 1000))
      ->group(group);
  drag->add_option("--intermediate-sweeps", h.intermediate_sweeps,
                   "Local sweeps on each intermediate level per cycle")
      ->check(CLI::Range(0, 1000))
      ->group(group);
  drag->add_option("--coarse-iterations", h.coarse_iterations,
                   "Newton iterations on the coarsest level per cycle")
      ->check(CLI::Range(0, 1000))
      ->group(group);
  drag->add_option("--intermediate-cycles", h.intermediate_cycles,
                   "Visits of the coarser levels per intermediate level (1: V-cycle, 2: W-cycle)")
      ->check(CLI::Range(1, 10))
      ->group(group);
  drag->add_option("--intermediate-relaxation", h.intermediate_relaxation,
                   "Over-relaxation factor of intermediate sweeps (1: plain Gauss-Seidel)")
      ->check(CLI::Range(1.0, 1.99))
      ->group(group);
  drag->add_option("--acceleration-history", h.acceleration_history,
                   "Anderson acceleration over this many cycles within one solve (0: off)")
      ->check(CLI::Range(0, 50))
      ->group(group);
  drag->add_option("--coarse-factor-reuse", h.coarse_factor_reuse,
                   "Coarse Newton steps per numeric factorization, beyond the first")
      ->check(CLI::Range(0, 100000))
      ->group(group);
  drag->add_option("--drag-factor-reuse", h.drag_factor_reuse,
                   "During a drag: coarse Newton steps per numeric factorization, beyond the first")
      ->check(CLI::Range(0, 100000))
      ->group(group);
  drag->add_option("--drag-factor-lag", h.drag_factor_lag,
                   "During a drag: coarse steps a background refactorization has before its "
                   "factor takes over (-1: automatic, 0: refactorize in the foreground)")
      ->check(CLI::Range(-1, 100000))
      ->group(group);

  const Command quality = register_bench_quality(*bench);

  return {bench, [engine, engine_args, drag, drag_args, quality]() -> int {
            if (engine->parsed()) return run_bench_engine(*engine_args);
            if (drag->parsed()) return run_bench_drag(*drag_args);
            if (quality.subcommand->parsed()) return quality.run();
            return 1;  // require_subcommand(1) makes this unreachable
          }};
}

}  // namespace primo::app
