#pragma once
// Soft selection (Blender's proportional editing) for a handle: its influence fades over a
// radius. PriMo's handles move their faces rigidly, so a fading handle is a handle plus springs
// on the free faces around it: each face whose rest centroid lies within `radius` (straight-
// line distance in the rest pose) of the nearest rest centroid of the handle's faces is pulled
// towards where the handle's rigid motion takes it, with a weight w that falls from 1 at the
// handle to 0 at the radius by Blender's "smooth" falloff, 3t^2 - 2t^3 with t = 1 - d / r.
// The springs are the scenario format's zero-rest-length forces, one a face, so `primo deform`
// solves what the editor shows: the face's stiffness is k w |F| / sum |F| (the areas over the
// falloff's faces), which makes their energy k times the weighted mean of the squared
// distances, independent of the mesh's resolution as a force's is.

#include <memory>
#include <vector>

#include "mesh_topology.h"
#include "primo/model/constraints.h"
#include "selection.h"

namespace primo::editor {

struct FalloffFace {
  int face = -1;
  double weight = 0.0;     // 0 < weight <= 1
  // w |F| / sum |F|: the face's force stiffness is the handle's stiffness k times this.
  double share = 0.0;
  Vec3 rest_centroid = Vec3::Zero();
  bool operator==(const FalloffFace& o) const {
    return face == o.face && weight == o.weight && share == o.share &&
           rest_centroid == o.rest_centroid;
  }
};
using FalloffFaces = std::shared_ptr<const std::vector<FalloffFace>>;  // null: none

// Blender's smooth falloff of t = 1 - distance / radius (1 at the handle, 0 at the radius).
double smooth_falloff(double t);

// The faces within `radius` of `handle_faces` that are not `taken` (in any group), by face
// index, with their weights and shares. Empty for a radius <= 0 or nothing in reach.
std::vector<FalloffFace> falloff_faces(const MeshTopology& topology,
                                       const std::vector<int>& handle_faces, double radius,
                                       const FaceMask& taken);

// Where the handle's motion takes each falloff face, as the force's target offset.
Vec3 falloff_target_offset(const FalloffFace& face, const RigidTransform& motion);

}  // namespace primo::editor
