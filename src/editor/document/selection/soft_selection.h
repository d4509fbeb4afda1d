#pragma once
// Soft selection (Blender's proportional editing) for a handle: its influence fades over a
// radius. PriMo's handles move their faces rigidly, so a fading handle is a handle plus springs
// on the free faces around it: each face whose rest centroid lies within `radius` (straight-
// line distance in the rest pose) of the nearest rest centroid of the handle's faces is pulled
// towards where the handle's rigid motion takes it, with a weight w that falls from 1 at the
// handle to 0 at the radius by Blender's "smooth" falloff, 3t^2 - 2t^3 with t = 1 - d / r.
// The springs themselves (their stiffness shares and targets) are
// primo/model/falloff_springs.h, shared with the replay of recorded sessions.

#include <memory>
#include <vector>

#include "mesh_topology.h"
#include "primo/model/falloff_springs.h"
#include "selection.h"

namespace primo::editor {

using FalloffFace = FalloffSpring;
using FalloffFaces = std::shared_ptr<const std::vector<FalloffFace>>;  // null: none

// Blender's smooth falloff of t = 1 - distance / radius (1 at the handle, 0 at the radius).
double smooth_falloff(double t);

// The faces within `radius` of `handle_faces` that are not `taken` (in any group), by face
// index, with their weights and shares. Empty for a radius <= 0 or nothing in reach.
std::vector<FalloffFace> falloff_faces(const MeshTopology& topology,
                                       const std::vector<int>& handle_faces, double radius,
                                       const FaceMask& taken);

}  // namespace primo::editor
