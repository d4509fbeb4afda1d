#pragma once
// Symmetry: which face mirrors which across a plane through the mesh's centre perpendicular
// to X, Y or Z, and the edits that follow a mirror (selection and painting copy their changes
// to the twin faces; a mirrored handle takes its twin's pose reflected).
//
// Two ways to find twins, as Blender's "Mirror" and "Topology Mirror" do:
//  - by position: faces are paired one to one, nearest pairs first, where one's reflected
//    centroid lands within a reach of mean edge lengths of the other's (the plane is moved to
//    the median midpoint of near pairs first: a scan is rarely centred on its bounding box).
//    Exact for a symmetric mesh placed on the plane; on a scan, where the two sides are
//    tessellated differently and posed a little differently, the faces that find no partner
//    within the reach stay without a twin.
//  - by topology: from a seed pair of faces, twins spread across shared edges with the
//    faces' vertex order reversed (a reflection reverses orientation). A mesh whose
//    connectivity is symmetric is matched completely however it is placed or posed. Seeds come
//    from the position match; a seed whose spread contradicts itself is dropped.
// The match covering more faces wins (topology on a tie).

#include <vector>

#include "edit_state.h"
#include "handle_model.h"
#include "document/selection/mesh_topology.h"
#include "document/selection/selection.h"

namespace primo::editor {

struct MirrorMap {
  int axis = 0;                // 0 x, 1 y, 2 z
  double plane = 0.0;          // the plane's coordinate on that axis
  std::vector<int> face_twin;  // per face: its mirror face (itself on the plane), -1 none
  int matched = 0;             // faces with a twin
  bool by_topology = false;

  int twin(int face) const { return face_twin[size_t(face)]; }
};

// How far a face's reflected centroid may land from its twin's centroid, in mean edge lengths
// of the larger of the two faces. On the 29k-face armadillo scan, of the faces within 0.05 of
// the plane (where its shape is symmetric and only the tessellation differs) 0.5 edges matched
// 56%, 1 edge 83%, 1.5 edges 90%, 2 edges 91%: past 1.5 only the posing differs, and a twin
// further off would be another part of the body.
inline constexpr double kMirrorReach = 1.5;
MirrorMap match_mirror_by_position(const MeshTopology& topology, int axis,
                                   double reach = kMirrorReach);
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

// Per face: 1 where the map has no twin for it (edits there reach one side only).
std::vector<char> faces_without_twin(const MirrorMap& map);

// The twins of `faces` that are not in `faces` (sorted).
std::vector<int> mirror_faces(const std::vector<int>& faces, const MirrorMap& map);

// The pose of `twin` that is `source`'s pose reflected: twin moves as source does, seen in a
// mirror. Exact when twin's faces are the mirror image of source's.
Pose mirrored_pose(const HandleGroup& source, const HandleGroup& twin, const MirrorMap& map);

}  // namespace primo::editor
