#pragma once
// Vertex mode: the selection as vertices, one byte per vertex, and how it meets PriMo's
// handles, which are faces (prisms). A handle made from selected vertices takes every face
// touching one of them, the rule of the scenario format's {"vertices": [...]} selection.
// Switching modes converts as Blender does: faces to their corners, and vertices to the faces
// whose corners are all selected, so that face -> vertex -> face gives the faces back.

#include <vector>

#include "face_visibility.h"
#include "mesh_topology.h"
#include "selection.h"

namespace primo::editor {

using VertexMask = std::vector<std::uint8_t>;

enum class SelectionMode { Faces, Vertices };
const char* selection_mode_label(SelectionMode mode);

// The corners of the selected faces.
VertexMask vertices_of_faces(const MeshTopology& topology, const FaceMask& faces);
// The faces whose corners are all selected.
FaceMask faces_within_vertices(const MeshTopology& topology, const VertexMask& vertices);
// The faces with at least one selected corner (what a handle takes), as a mask.
FaceMask faces_touching_vertices(const MeshTopology& topology, const VertexMask& vertices);
// The corners of faces in `faces` (a list), for picking: the vertices a gesture can reach
// are the corners of the faces it reaches.
VertexMask corners_of(const MeshTopology& topology, const std::vector<int>& faces);

// What vertex mode draws as points: the corners of the faces shown, and the selected vertices
// among them (indices into the mesh's vertices).
std::vector<unsigned> shown_vertices(const MeshTopology& topology, const HiddenFaces& hidden);
std::vector<unsigned> selected_vertices(const VertexMask& vertices, const HiddenFaces& hidden,
                                        const MeshTopology& topology);

}  // namespace primo::editor
