#pragma once
// Exact self-intersection test of a polygon mesh. The implementation uses CGAL (heavy
// headers), which stays in self_intersections.cpp.

#include <utility>
#include <vector>

#include "primo/mesh/mesh.h"

namespace primo::quality {

struct SelfIntersections {
  // Pairs (f, g), f < g, of distinct faces of the mesh whose triangles intersect in more than
  // the vertices and edges they share, sorted, without duplicates.
  std::vector<std::pair<int, int>> face_pairs;
  // Triangles of zero area (collinear corners). CGAL reports each only with itself and tests
  // no other triangle against it, so a non-zero count means the pair count may be low.
  int degenerate_triangles = 0;
};

// Triangulates a copy of the mesh (each n-gon fanned from its first corner; triangles of one
// face never count against each other) and finds every intersecting triangle pair with CGAL.
SelfIntersections find_self_intersections(const Mesh& mesh);

}  // namespace primo::quality
