#pragma once
// The editor's setup as a scenario file (docs/scenario-format.md) and back, so that
// `primo deform` reproduces what the editor shows:
//  - painted factors become `regions` with {"faces": [...]}, one per distinct value;
//  - Spring groups become `forces` (target_offset = the dragged translation);
//  - every other group becomes a `handles` entry with {"faces": [...]} and its pose written
//    as translate / axis / angle_deg / center (center = the group's rest centroid).
// The scenario format has no "fixed region": those are written as fix "all" handles, and
// reading a fix "all" handle with an identity transform gives a Fixed region again.

#include <string>

#include "edit_state.h"
#include "primo/scenario/scenario.h"

namespace primo::editor {

// `mesh_path` is the mesh file the editor opened; it is written relative to the scenario's
// folder when both paths allow it.
// With `motions` (the solver's per-face motions of the pose shown) the scenario carries them
// as its solved state; fixed regions are listed under `editor.fixed_regions`, and the model's
// orientation under `editor.orientation` unless the mesh alone gives it (model_orientation.h).
Scenario export_scenario(const EditState& state, const std::string& mesh_path,
                         const std::string& scenario_path, const SolverSpec& solver,
                         const std::vector<RigidTransform>* motions = nullptr);

// The edit state a resolved scenario describes on its mesh. A fix "all" handle is a fixed
// region when `editor.fixed_regions` lists it, else (a file without `editor`) when its
// transform is the identity. `editor.orientation`, when given, is the state's orientation
// (else it keeps the default; load_document then asks the mesh).
EditState import_scenario(const Scenario& scenario, const ResolvedScenario& resolved,
                          const MeshTopology& topology);

}  // namespace primo::editor
