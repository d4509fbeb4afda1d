#pragma once
// A handle's pivot: the point it turns about (HandleGroup::center, the scenario format's
// transform `center`), a point of the handle's rest pose that moves with it. An arm turns about
// its shoulder once its pivot is there. Moving the pivot never moves the handle's faces: the
// translation is re-expressed for the new centre, so the rigid motion stays the same.

#include <vector>

#include "handle_model.h"
#include "document/selection/mesh_topology.h"

namespace primo::editor {

// The rest area-weighted centroid of the handle's faces: where a new handle's pivot is.
Vec3 rest_centroid(const HandleGroup& group, const MeshTopology& topology);

// Where the handle's faces are now, as one rigid motion of its rest pose: the transform it
// prescribes, or for an orientation-only handle (its position follows the solve) its rotation
// about where its faces are in `current`.
RigidTransform handle_motion(const HandleGroup& group, const MeshTopology& topology,
                             const std::vector<Vec3>& current);

// The rest point that `motion` carries to `world`: where a pivot placed at `world` in the view
// is in the handle's rest pose.
Vec3 rest_point_of(const RigidTransform& motion, const Vec3& world);

// Makes `rest_point` the handle's pivot. Its rigid motion stays as it was (translate becomes
// translate + (R - I)(new - old)), so the faces stay where they are and only what a rotation
// turns about changes.
void move_pivot(HandleGroup& group, const Vec3& rest_point);

}  // namespace primo::editor
