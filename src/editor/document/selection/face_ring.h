#pragma once
// Edge loops as PriMo selects them: its handles are faces, so the loop across an edge is the
// ring of faces it crosses (Blender's face ring, what Alt+click selects in face mode). From
// the edge, the walk goes through the quad on each side to that quad's opposite edge, and on
// to the face across it, until a face that is not a quad, a boundary, or the start again (a
// ring around a cylinder closes).

#include <vector>

#include "mesh_topology.h"

namespace primo::editor {

// The faces that contain both vertices a and b (the edge's one or two faces).
std::vector<int> faces_across_edge(const MeshTopology& topology, int a, int b);

// The quads of the ring across edge (a, b), sorted; empty when neither face at the edge is a
// quad (a loop needs quads) or (a, b) is not an edge.
std::vector<int> face_ring(const MeshTopology& topology, int a, int b);

// An edge of a face: its two vertices in the face's order.
struct FaceEdge {
  int a = -1, b = -1;
};
// The edge of face f nearest to `point` among the vertices' 2D positions `points` (the
// editor's: where they are on screen), measured to the whole segment.
FaceEdge nearest_edge_of_face(const MeshTopology& topology, int f,
                              const std::vector<Eigen::Vector2d>& points,
                              const Eigen::Vector2d& point);

}  // namespace primo::editor
