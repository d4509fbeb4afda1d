#pragma once
// A coarse stand-in for big meshes while the camera moves: vertex clustering on a grid over
// the rest shape. Each occupied cell keeps one of its vertices; a triangle survives when its
// corners fall in three different cells and is re-indexed to those kept vertices. The proxy
// indexes the mesh's own vertex buffer, so it follows every deformation for free, and each
// proxy triangle keeps the face it came from (for overlay colours).

#include <vector>

#include "mesh_topology.h"

namespace primo::editor {

struct ProxyTriangles {
  std::vector<unsigned> triangles;  // 3 vertex indices (of the full mesh) per triangle
  std::vector<int> triangle_face;   // source face per triangle
  bool empty() const { return triangle_face.empty(); }
};

// Clusters until the proxy has at most about `max_triangles` triangles (the finest grid that
// does). Empty when the mesh itself has no more than that.
ProxyTriangles cluster_triangles(const MeshTopology& topology, int max_triangles);

}  // namespace primo::editor
