#pragma once
// Which frame the gizmo's axes follow, as Blender's transform orientations: the world's axes,
// the handle's own (its rest axes turned by its current rotation), its surface normal (the
// rest area-weighted mean normal of its faces, turned by its rotation, as Z), or the view's
// (right, up, towards the viewer). The arrows, the rings and the axis-constrained drags all
// use the chosen frame.

#include <glm/glm.hpp>

#include "camera.h"
#include "document/handle_model.h"
#include "document/selection/mesh_topology.h"

namespace primo::editor {

enum class GizmoOrientation { Global, Local, Normal, View };
inline constexpr int kGizmoOrientations = 4;

const char* orientation_label(GizmoOrientation orientation);  // "Global", "Local", ...
// The next in the list above, after View Global again (the key that cycles them).
GizmoOrientation next_orientation(GizmoOrientation orientation);

// The rest area-weighted mean normal of `faces` (unit): the sum of their vector areas. Where
// they cancel (a closed group), the rest Z axis.
Vec3 rest_mean_normal(const MeshTopology& topology, const std::vector<int>& faces);

// The gizmo's X, Y and Z axes as the columns of a rotation (right-handed, unit) for the
// handle `group` as posed now.
glm::dmat3 gizmo_axes(GizmoOrientation orientation, const HandleGroup& group,
                      const MeshTopology& topology, const Camera& camera);

}  // namespace primo::editor
