#pragma once
// One opened mesh with everything edited on it: the live EditState and its undo history,
// plus where it came from (mesh file, scenario file, the scenario's solver settings).

#include <memory>
#include <string>

#include "edit_state.h"
#include "document/selection/mesh_topology.h"
#include "proxy_mesh.h"
#include "primo/mesh/mesh_attributes.h"
#include "primo/scenario/scenario.h"
#include "undo_stack.h"

namespace primo::editor {

struct Document {
  std::shared_ptr<const Mesh> mesh;
  std::shared_ptr<const MeshTopology> topology;
  // Drawn instead of the full mesh while the camera moves (empty for small meshes), built in
  // the background.
  std::shared_ptr<ProxyBuild> proxy;
  std::string mesh_path;      // the mesh file
  std::string scenario_path;  // the scenario it was opened from or last saved to ("" if none)
  // What reading a scene file (glTF, FBX, COLLADA, 3MF) joined, merged or left out, without the
  // path: "merged 194 vertex copies ...; ignored: 1 material, UVs". "" for other formats.
  std::string load_note;
  // UVs, normals, colours and materials as read, for "Export deformed mesh" to write back.
  std::shared_ptr<const MeshAttributes> attributes = std::make_shared<const MeshAttributes>();
  SolverSpec solver;          // max_iterations / tolerance / method of a settle and of exports
  // The opened scenario's solved state, handed to the solver with the first problem.
  std::vector<RigidTransform> start_motions;
  EditState state;            // live: gestures edit it, `commit` records it
  EditState saved_state;      // as opened or last saved: what "unsaved changes" compares with
  UndoStack history;

  int n_faces() const { return topology->n_faces; }
  // Records the live state as one undo step; false when nothing changed.
  bool commit(const std::string& label) { return history.push(label, state); }
};

// True for paths the editor opens as scenarios (".json").
bool is_scenario_path(const std::string& path);

// Meshes of more than this many triangles get a stand-in for motion (Document::proxy). A
// software renderer draws about 3 million triangles a second: a 60,000-triangle mesh already
// costs 20 ms a frame. A GPU draws hundreds of millions: there a mesh is drawn in full in
// motion up to 2 million (a few milliseconds a frame even on an integrated one), and a big
// mesh's decimation (1-2 core-seconds at 240k faces) is not spent on every open.
inline constexpr int kStandInAboveInSoftware = 60000;
inline constexpr int kStandInAboveOnGpu = 2000000;

// Reads a mesh (OBJ, OFF, PLY, STL, OM, glTF/GLB, FBX, DAE, 3MF) or a scenario with its mesh,
// resolved. Slow for big meshes: call it off the UI thread. Throws primo::Error with a one-line
// message.
std::unique_ptr<Document> load_document(const std::string& path,
                                        int stand_in_above = kStandInAboveInSoftware);

// A document for a mesh already in memory (tests, generated meshes).
std::unique_ptr<Document> make_document(Mesh mesh, std::string mesh_path,
                                        int stand_in_above = kStandInAboveInSoftware);

}  // namespace primo::editor
