// `primo metrics REST DEFORMED [--json FILE]`: how a deformed mesh differs from its rest mesh
// (docs/quality.md): volume (open boundaries capped), area, dihedral angles, edge lengths,
// fold-overs and exact self-intersections. Any two meshes with the same connectivity.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "quality/mesh_quality.h"
#include "quality/quality_report.h"

namespace primo::app {
namespace {

struct MetricsArguments {
  std::string rest;
  std::string deformed;
  std::string json;
};

void print_metrics(const quality::QualityMetrics& m) {
  std::printf("%-34s %d vertices, %d faces, %d interior edges, %d boundary loops\n", "mesh",
              m.vertices, m.faces, m.interior_edges, m.boundary_loops);
  std::printf("%-34s %s  (%.6g -> %.6g)\n", "volume change % (capped)",
              quality::format_volume_change(m).c_str(), m.rest_volume, m.deformed_volume);
  std::printf("%-34s %+.2f  (%.6g -> %.6g)\n", "area change %", m.area_change_percent,
              m.rest_area, m.deformed_area);
  std::printf("%-34s %.3f\n", "dihedral change RMS (deg)", m.dihedral_change_rms_deg);
  std::printf("%-34s %.3f\n", "dihedral change max (deg)", m.dihedral_change_max_deg);
  std::printf("%-34s %.3f\n", "edge length change RMS %", m.edge_change_rms_percent);
  std::printf("%-34s %.3f\n", "edge length change max %", m.edge_change_max_percent);
  std::printf("%-34s %d\n", "fold-overs (normals > 150 deg)", m.fold_overs);
  std::printf("%-34s %d\n", "self-intersecting face pairs", m.self_intersecting_pairs);
  if (m.degenerate_triangles > 0)
    std::printf("%-34s %d (pairs with them are not tested)\n", "degenerate triangles",
                m.degenerate_triangles);
}

int run_metrics(const MetricsArguments& args) {
  const Mesh rest = load_mesh(args.rest);
  const Mesh deformed = load_mesh(args.deformed);
  const quality::QualityMetrics metrics =
      quality::measure_quality(rest, deformed, args.rest, args.deformed);
  std::printf("primo metrics %s -> %s\n\n", args.rest.c_str(), args.deformed.c_str());
  print_metrics(metrics);
  if (!args.json.empty()) {
    nlohmann::json out = quality::quality_json(metrics);
    out["rest"] = args.rest;
    out["deformed"] = args.deformed;
    write_text_atomically(args.json, out.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

Command register_metrics(CLI::App& app) {
  auto args = std::make_shared<MetricsArguments>();
  CLI::App* cmd = app.add_subcommand(
      "metrics", "Compare a deformed mesh with its rest mesh (same connectivity): volume, area, "
                 "dihedral and edge changes, fold-overs, self-intersections");
  cmd->add_option("rest", args->rest, "Rest mesh (.obj .off .ply .stl .om .gltf .glb .fbx .dae .3mf)")
      ->required();
  cmd->add_option("deformed", args->deformed, "Deformed mesh with the same vertices and faces")
      ->required();
  cmd->add_option("--json", args->json, "Also write the metrics as JSON");
  return {cmd, [args] { return run_metrics(*args); }};
}

}  // namespace primo::app
