#pragma once
// `primo bench quality [SCENARIO...] [--case NAME]... [--json FILE] [--output-dir DIR]
//                      [--mesh-dir DIR] [--peer-max-iterations N] [--half-thickness H]
//                      [--scenario-material]`
//
// How smooth and how faithful large one-step edits are (docs/quality.md): every case
// is a scenario, solved by PriMo exactly as `primo deform` solves it, and by CGAL's ARAP and
// SR-ARAP (Surface_mesh_deformation) on the same handles in the same run. Each result is
// measured against the rest mesh (quality/mesh_quality.h). Without scenario arguments the
// cases are assets/scenarios/quality/*.json: the paper's Figure 2 cylinder (bend 90 and 180
// degrees, twist 180 degrees, shift) and real meshes from ../shared/meshes.

#include <string>
#include <vector>

#include "primo/model/constraints.h"
#include "quality/cgal_deformation.h"

namespace primo::bench {

struct QualityBenchOptions {
  std::vector<std::string> scenarios;  // none: every case of assets/scenarios/quality
  std::vector<std::string> cases;      // only these (file names without .json)
  std::string json;
  std::string output_dir;  // every result mesh as CASE-primo.obj, CASE-arap.obj, ...
  std::string mesh_dir;    // where a case's mesh is when not at the scenario's own path
  quality::PeerSettings peer;
  // The material PriMo is measured with: the product's default unless told otherwise, so
  // the table shows what a new user gets (docs/quality.md, "Default material").
  double half_thickness = kDefaultHalfThickness;
  bool scenario_material = false;  // the scenario's own prisms.height / half_thickness
};

// Prints the table; returns the exit code. Throws primo::Error on bad options or files.
int run_quality_bench(const QualityBenchOptions& options);

}  // namespace primo::bench
