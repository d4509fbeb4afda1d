#pragma once
// Symmetry: which face mirrors which across a plane through the mesh's centre perpendicular
// to X, Y or Z, and the edits that follow a mirror (selection and painting copy their changes
// to the twin faces; a mirrored handle takes its twin's pose reflected).
//
// Two ways to find twins, as Blender's "Mirror" and "Topology Mirror" do:
//  - by position: the face whose centroid is nearest the reflected centroid, within half a
//    face size. Exact for a symmetric mesh placed on the plane; it misses faces where the
//    mesh is a little off the plane, turned, or posed asymmetrically.
//  - by topology: from a seed pair of faces, twins spread across shared edges with the
//    faces' vertex order reversed (a reflection reverses orientation). A mesh whose
//    connectivity is symmetric is matched completely however it is placed or posed. Seeds come
//    from the position match; a seed whose spread contradicts itself is dropped.
// The match covering more faces wins (topology on a tie).

#include <vector>

#include "edit_state.h"
#include "handle_model.h"
#include "mesh_topology.h"
#include "selection.h"

namespace primo::editor {

struct MirrorMap {
  int axis = 0;                // 0 x, 1 y, 2 z
  double plane = 0.0;          // the plane's coordinate on that axis (bounding-box centre)
  std::vector<int> face_twin;  // per face: its mirror face (itself on the plane), -1 none
  int matched = 0;             // faces with a twin
  bool by_topology = false;

  int twin(int face) const { return face_twin[size_t(face)]; }
};

MirrorMap match_mirror_by_position(const MeshTopology& topology, int axis);
// Empty (no face matched) when the connectivity is not symmetric.
MirrorMap match_mirror_by_topology(const MeshTopology& topology, int axis);
// The better of the two.
MirrorMap match_mirror(const MeshTopology& topology, int axis);

const char* axis_name(int axis);  // "X", "Y", "Z"

// The point reflected across the map's plane.
Vec3 reflect(const MirrorMap& map, const Vec3& p);

// Faces whose entry changed from `before` to `after` get the same new entry at their twins.
void mirror_changes(const FaceMask& before, FaceMask& after, const MirrorMap& map);
FactorArray mirror_changes(const FactorArray& before, const FactorArray& after, int n_faces,
                           const MirrorMap& map);

// The twins of `faces` that are not in `faces` (sorted).
std::vector<int> mirror_faces(const std::vector<int>& faces, const MirrorMap& map);

// The pose of `twin` that is `source`'s pose reflected: twin moves as source does, seen in a
// mirror. Exact when twin's faces are the mirror image of source's.
Pose mirrored_pose(const HandleGroup& source, const HandleGroup& twin, const MirrorMap& map);

}  // namespace primo::editor
