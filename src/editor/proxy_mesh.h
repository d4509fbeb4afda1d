#pragma once
// A coarse stand-in for big meshes while the camera moves or a gesture is under way: the rest
// shape decimated by OpenMesh's quadric-error halfedge collapses. A halfedge collapse keeps the
// surviving vertices where they are, so the proxy indexes the mesh's own vertex buffer and
// follows every deformation for free; each proxy triangle keeps the face it came from (for
// overlay colours).
//
// Why decimation rather than vertex clustering (what this was before): clustering merges the
// two sides of thin parts and joins unrelated sheets that share a grid cell, so the stand-in
// showed holes, non-manifold fins and slivers. Collapses that would change the topology, flip
// a triangle or make a needle are refused, boundaries are kept, and the result is a manifold
// surface with the mesh's own orientation.

#include <atomic>
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include "mesh_topology.h"

namespace primo::editor {

struct ProxyTriangles {
  std::vector<unsigned> triangles;  // 3 vertex indices (of the full mesh) per triangle
  std::vector<int> triangle_face;   // source face per triangle
  bool empty() const { return triangle_face.empty(); }
};

// Decimates until the proxy has at most about `max_triangles` triangles. Empty when the mesh
// itself has no more than that. Triangles the decimater cannot take (a non-manifold fan) stay
// as they are, with their corners kept, so nothing is left out. A big mesh is decimated in
// spatial parts on `threads` threads (0: one per core), then joined and decimated once more
// to the budget; the result is the same on any number of threads.
// Returns early, empty, once `cancel` (if given) is set.
ProxyTriangles decimate_triangles(const MeshTopology& topology, int max_triangles,
                                  const std::atomic<bool>* cancel = nullptr, int threads = 0);

// The proxy built off the window's thread: decimating a 100k-face mesh took about two seconds
// on one core, and a mesh should open at once (it is drawn in full until its proxy is ready).
// Destroying the build cancels it and waits only for the decimater's next check.
class ProxyBuild {
 public:
  ProxyBuild(std::shared_ptr<const MeshTopology> topology, int max_triangles);
  ~ProxyBuild();
  ProxyBuild(const ProxyBuild&) = delete;
  ProxyBuild& operator=(const ProxyBuild&) = delete;

  // The finished proxy (empty for small meshes), or null while it is being built.
  // For one thread at a time (the UI's).
  const ProxyTriangles* ready();
  // Blocks until the proxy is built (tests, screenshots).
  const ProxyTriangles& wait();

 private:
  std::atomic<bool> cancel_{false};
  std::future<ProxyTriangles> future_;
  std::optional<ProxyTriangles> result_;
};

}  // namespace primo::editor
