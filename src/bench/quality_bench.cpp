#include "quality_bench.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "inputs.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "primo/scenario/scenario.h"
#include "primo/scenario/scenario_deformer.h"
#include "primo/scenario/scenario_solve.h"
#include "quality/cgal_deformation.h"
#include "quality/mesh_quality.h"
#include "quality/quality_report.h"
#include "quality/stopwatch.h"
#include "report.h"

namespace fs = std::filesystem;

namespace primo::bench {
namespace {

// One method's result on one case.
struct MethodRun {
  std::string method;  // "PriMo", "ARAP", "SR-ARAP"
  quality::QualityMetrics metrics;
  quality::Seconds seconds;  // set-up and solve
  std::optional<SolveReport> report;  // PriMo only
  std::string solver;                 // PriMo only: which of its solvers
};

struct CaseResult {
  std::string name;  // the scenario's file name without .json
  std::string scenario;
  std::string mesh_path;
  std::string skipped;     // why the case did not run
  std::string peers_note;  // why the peers did not run
  std::vector<MethodRun> runs;
};

// The cases: the scenarios given, else every scenario of the shipped quality folder, in file
// name order; --case keeps those whose name (file name without .json) is listed.
std::vector<std::string> case_scenarios(const QualityBenchOptions& args) {
  std::vector<std::string> scenarios = args.scenarios;
  if (scenarios.empty()) {
    const fs::path folder = fs::path(asset_dir()) / "scenarios" / "quality";
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
      throw Error(folder.string() + ": no such folder (set PRIMO_ASSET_DIR or pass scenarios)");
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".json") scenarios.push_back(entry.path().string());
    std::sort(scenarios.begin(), scenarios.end());
  }
  if (args.cases.empty()) return scenarios;
  std::vector<std::string> kept;
  for (const std::string& name : args.cases) {
    const auto found = std::find_if(scenarios.begin(), scenarios.end(), [&](const std::string& s) {
      return fs::path(s).stem().string() == name;
    });
    if (found == scenarios.end())
      throw Error("--case " + name + ": no scenario " + name + ".json among the cases");
    kept.push_back(*found);
  }
  return kept;
}

// The scenario's mesh where the scenario says; else its file name in --mesh-dir, or in a
// shared/meshes folder above the working directory or the executable. "" when absent.
std::string find_case_mesh(const Scenario& scenario, const std::string& mesh_dir) {
  std::error_code ec;
  if (fs::is_regular_file(scenario.mesh_path, ec)) return scenario.mesh_path;
  const std::string name = fs::path(scenario.mesh).filename().string();
  if (mesh_dir.empty()) return find_shared_mesh(name);
  const fs::path candidate = fs::path(mesh_dir) / name;
  return fs::is_regular_file(candidate, ec) ? candidate.string() : "";
}

// Why CGAL's ARAP cannot be given the same problem, or "" when it can: it deforms triangle
// meshes with fixed target positions for control vertices, nothing else.
std::string why_no_peers(const Mesh& mesh, const ResolvedScenario& resolved) {
  for (auto f : mesh.faces())
    if (f.valence() != 3)
      return "no peers: polygon mesh (face " + std::to_string(f.idx()) + " has " +
             std::to_string(f.valence()) + " corners); CGAL's deformation needs triangles";
  if (!resolved.forces.empty()) return "no peers: the scenario has forces, which ARAP does not model";
  for (const Handle& h : resolved.handles)
    if (h.fix != Fix::All)
      return "no peers: handle '" + h.name +
             "' is not fix \"all\"; ARAP only takes prescribed vertex positions";
  if (resolved.handles.empty()) return "no peers: no handles";
  return "";
}

// The peers' control vertices: every vertex of a handle face, its target the handle's motion
// applied to its rest position. A vertex on two handles keeps the first handle's target.
void handle_targets(const Mesh& mesh, const std::vector<Handle>& handles,
                    std::vector<int>& control_vertices, std::vector<Vec3>& targets) {
  std::vector<bool> taken(mesh.n_vertices(), false);
  for (const Handle& h : handles)
    for (int f : h.faces)
      for (auto v : mesh.fv_range(mesh.face_handle(unsigned(f)))) {
        if (taken[size_t(v.idx())]) continue;
        taken[size_t(v.idx())] = true;
        control_vertices.push_back(v.idx());
        targets.push_back(h.transform.apply(mesh.point(v)));
      }
}

Mesh with_positions(const Mesh& mesh, const std::vector<Vec3>& positions) {
  Mesh result = mesh;
  for (auto v : result.vertices()) result.point(v) = positions[size_t(v.idx())];
  return result;
}

void save_result(const Mesh& result, const std::string& output_dir, const std::string& case_name,
                 const std::string& method) {
  if (output_dir.empty()) return;
  std::string suffix = method;
  std::transform(suffix.begin(), suffix.end(), suffix.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  save_mesh(result, (fs::path(output_dir) / (case_name + "-" + suffix + ".obj")).string());
}

CaseResult run_case(const std::string& scenario_path, const QualityBenchOptions& args) {
  CaseResult c;
  c.scenario = scenario_path;
  c.name = fs::path(scenario_path).stem().string();
  const Scenario scenario = load_scenario(scenario_path);
  c.mesh_path = find_case_mesh(scenario, args.mesh_dir);
  if (c.mesh_path.empty()) {
    c.skipped = "skipped: " + fs::path(scenario.mesh).filename().string() + " not found (" +
                (args.mesh_dir.empty() ? std::string("no shared/meshes folder has it; pass --mesh-dir")
                                       : "not in --mesh-dir " + args.mesh_dir) +
                ")";
    return c;
  }
  const Mesh mesh = load_mesh(c.mesh_path);
  ResolvedScenario resolved = resolve_scenario(scenario, mesh);
  if (!args.scenario_material) {
    resolved.prisms.height = args.half_thickness;
    resolved.prisms.height_unit = HeightUnit::Diagonal;
  }

  // PriMo as `primo deform` runs it: the scenario's handles, forces and solver settings, and
  // the material chosen above.
  {
    MethodRun run;
    run.method = "PriMo";
    const quality::Stopwatch stopwatch;
    Deformer deformer = make_scenario_deformer(mesh, resolved);
    const SolveOptions options = scenario_solve_options(resolved.solver, mesh.n_faces());
    run.report = deformer.solve(options);
    run.seconds = stopwatch.elapsed();
    run.solver = solve_method_name(options.method);
    const Mesh result = deformer.deformed_mesh(mesh);
    run.metrics = quality::measure_quality(mesh, result, c.mesh_path, c.name + " (PriMo)");
    save_result(result, args.output_dir, c.name, run.method);
    c.runs.push_back(std::move(run));
  }

  c.peers_note = why_no_peers(mesh, resolved);
  if (!c.peers_note.empty()) return c;
  std::vector<int> control_vertices;
  std::vector<Vec3> targets;
  handle_targets(mesh, resolved.handles, control_vertices, targets);
  for (quality::PeerMethod method : {quality::PeerMethod::Arap, quality::PeerMethod::SrArap}) {
    MethodRun run;
    run.method = quality::peer_method_name(method);
    const quality::PeerResult peer =
        quality::deform_with_cgal(mesh, control_vertices, targets, method, args.peer);
    run.seconds = peer.seconds;
    const Mesh result = with_positions(mesh, peer.positions);
    run.metrics = quality::measure_quality(mesh, result, c.mesh_path, c.name + " (" + run.method + ")");
    save_result(result, args.output_dir, c.name, run.method);
    c.runs.push_back(std::move(run));
  }
  return c;
}

// PriMo's time over SR-ARAP's on the same case, when both ran: of wall times, or of CPU times.
std::optional<double> time_ratio(const CaseResult& c, bool cpu = false) {
  const MethodRun* primo = nullptr;
  const MethodRun* sr_arap = nullptr;
  for (const MethodRun& r : c.runs) {
    if (r.method == "PriMo") primo = &r;
    if (r.method == "SR-ARAP") sr_arap = &r;
  }
  if (!primo || !sr_arap) return std::nullopt;
  const double ours = cpu ? primo->seconds.cpu : primo->seconds.wall;
  const double theirs = cpu ? sr_arap->seconds.cpu : sr_arap->seconds.wall;
  if (!(theirs > 0)) return std::nullopt;
  return ours / theirs;
}

void print_header() {
  std::printf("%-20s %-7s %5s %6s %6s %7s %7s %7s %7s %5s %5s %10s %7s %6s %5s %5s\n", "case",
              "method", "faces", "vol %", "area %", "dih rms", "dih max", "edg rms", "edg max",
              "folds", "selfX", "energy", "wall s", "cpu s", "P/SR", "cpu");
}

void print_case(const CaseResult& c) {
  if (!c.skipped.empty()) {
    std::printf("%-20s %s\n", c.name.c_str(), c.skipped.c_str());
    return;
  }
  const std::optional<double> wall_ratio = time_ratio(c), cpu_ratio = time_ratio(c, true);
  for (const MethodRun& r : c.runs) {
    const quality::QualityMetrics& m = r.metrics;
    char energy[32] = "-", wall_text[32] = "-", cpu_text[32] = "-";
    if (r.report) std::snprintf(energy, sizeof energy, "%.4e", r.report->energy);
    if (r.report && wall_ratio) std::snprintf(wall_text, sizeof wall_text, "%.2f", *wall_ratio);
    if (r.report && cpu_ratio) std::snprintf(cpu_text, sizeof cpu_text, "%.2f", *cpu_ratio);
    std::printf(
        "%-20s %-7s %5d %6s %+6.1f %7.2f %7.2f %7.2f %7.2f %5d %5d %10s %7.2f %6.2f %5s %5s\n",
        c.name.c_str(), r.method.c_str(), m.faces, quality::format_volume_change(m).c_str(),
        m.area_change_percent, m.dihedral_change_rms_deg, m.dihedral_change_max_deg,
        m.edge_change_rms_percent, m.edge_change_max_percent, m.fold_overs,
        m.self_intersecting_pairs, energy, r.seconds.wall, r.seconds.cpu, wall_text, cpu_text);
  }
  if (!c.peers_note.empty()) std::printf("%-20s %s\n", "", c.peers_note.c_str());
  for (const MethodRun& r : c.runs)
    if (r.report && !r.report->converged)
      std::printf("%-20s PriMo stopped at solver.max_iterations (%d) before converging\n", "",
                  r.report->iterations);
}

nlohmann::json case_json(const CaseResult& c) {
  nlohmann::json j = {{"case", c.name}, {"scenario", c.scenario}};
  if (!c.skipped.empty()) {
    j["skipped"] = c.skipped;
    return j;
  }
  j["mesh"] = c.mesh_path;
  if (!c.peers_note.empty()) j["peers_note"] = c.peers_note;
  const auto or_null = [](std::optional<double> x) {
    return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
  };
  j["time_ratio_primo_over_sr_arap"] = or_null(time_ratio(c));
  j["cpu_time_ratio_primo_over_sr_arap"] = or_null(time_ratio(c, true));
  j["runs"] = nlohmann::json::array();
  for (const MethodRun& r : c.runs) {
    nlohmann::json run = {{"method", r.method},
                          {"seconds", r.seconds.wall},
                          {"cpu_seconds", r.seconds.cpu},
                          {"metrics", quality::quality_json(r.metrics)}};
    if (r.report) {
      run["solver"] = r.solver;
      run["energy"] = r.report->energy;
      run["iterations"] = r.report->iterations;
      run["converged"] = r.report->converged;
    }
    j["runs"].push_back(std::move(run));
  }
  return j;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

}  // namespace

int run_quality_bench(const QualityBenchOptions& args) {
  const std::vector<std::string> scenarios = case_scenarios(args);
  if (!args.output_dir.empty()) {
    std::error_code ec;
    fs::create_directories(args.output_dir, ec);
    if (!fs::is_directory(args.output_dir, ec))
      throw Error(args.output_dir + ": cannot create the output folder");
  }
  const std::string build = build_label("times");
  const quality::PeerSettings& peer = args.peer;
  std::printf("primo bench quality: %zu cases  [build: %s; %u hardware threads]\n", scenarios.size(),
              build.c_str(), std::thread::hardware_concurrency());
  const std::string material =
      args.scenario_material ? std::string("the scenario's prisms")
                             : "half_thickness " + std::to_string(args.half_thickness).substr(0, 6) +
                                   " of the diagonal";
  std::printf("PriMo: %s, the scenario's handles and solver settings, `primo deform`'s solver; "
              "peers: CGAL Surface_mesh_deformation, tolerance %g, at most %u iterations\n",
              material.c_str(), peer.tolerance, peer.max_iterations);
  std::printf("vol %%: capped volume change; dih: dihedral change (deg); edg: edge length change "
              "(%%); folds: normals > %.0f deg; selfX: self-intersecting face pairs; wall/cpu s: "
              "set-up + solve (cpu: process CPU time, all threads); P/SR, cpu: PriMo's wall and "
              "CPU time over SR-ARAP's\n\n",
              quality::kFoldOverDegrees);
  print_header();

  nlohmann::json out = {{"date", utc_now()},
                        {"build", build},
                        {"hardware_threads", std::thread::hardware_concurrency()},
                        {"primo_material", material},
                        {"peer_tolerance", peer.tolerance},
                        {"peer_max_iterations", peer.max_iterations},
                        {"cases", nlohmann::json::array()}};
  for (const std::string& scenario : scenarios) {
    const CaseResult c = run_case(scenario, args);
    print_case(c);
    std::fflush(stdout);
    out["cases"].push_back(case_json(c));
  }
  if (!args.json.empty()) write_text_atomically(args.json, out.dump(2) + "\n");
  return 0;
}

}  // namespace primo::bench
