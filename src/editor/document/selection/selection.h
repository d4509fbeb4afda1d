#pragma once
// Face selection: a mask with one byte per face, and the operations of the Select menu. The
// mask is what a brush, box or lasso gesture and the grow/shrink/invert commands act on.

#include <cstdint>
#include <vector>

#include "mesh_topology.h"

namespace primo::editor {

using FaceMask = std::vector<std::uint8_t>;

// How a gesture combines with the selection that was there before it.
enum class SelectOp {
  Replace,   // the gesture's faces only
  Add,       // union
  Subtract,  // difference
};

void apply_selection(FaceMask& mask, const std::vector<int>& faces, SelectOp op);
// Adds every face sharing a vertex with a selected face.
void grow_selection(FaceMask& mask, const MeshTopology& topology);
// Removes every selected face that shares a vertex with an unselected face.
void shrink_selection(FaceMask& mask, const MeshTopology& topology);
// Adds every face reachable from the selection across shared edges whose two faces' rest
// normals differ by at most `max_angle_deg` (180: the whole connected piece, as Blender's
// Select Linked; 30: up to sharp edges, as "by angle").
void select_linked(FaceMask& mask, const MeshTopology& topology, double max_angle_deg = 180.0);
void invert_selection(FaceMask& mask);
void clear_selection(FaceMask& mask);
void select_all(FaceMask& mask);

std::vector<int> selected_faces(const FaceMask& mask);
int count_selected(const FaceMask& mask);

}  // namespace primo::editor
