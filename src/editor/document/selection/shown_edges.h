#pragma once
// The wireframe of what is shown: the polygon edges of the faces that are not hidden
// (face_visibility.h), so that hiding a part leaves no wire cage of it behind.

#include <vector>

#include "face_visibility.h"
#include "mesh_topology.h"

namespace primo::editor {

// Pairs of vertex indices from topology.edges: those with at least one shown face.
std::vector<unsigned> shown_edges(const MeshTopology& topology, const HiddenFaces& hidden);

}  // namespace primo::editor
