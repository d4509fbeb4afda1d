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

#include "document/selection/mesh_topology.h"

namespace primo::editor {

struct ProxyTriangles {
  std::vector<unsigned> triangles;  // 3 vertex indices (of the full mesh) per triangle
  std::vector<int> triangle_face;   // source face per triangle
  bool empty() const { return triangle_face.empty(); }
};

// What the window tells a decimation while it runs, read at least every few hundred
// collapses.
struct DecimationSignals {
  std::atomic<bool> cancel{false};  // stop: the result is not wanted any more
  std::atomic<bool> paused{false};  // wait: the cores are needed elsewhere for now
};

// Decimates until the proxy has at most about `max_triangles` triangles. Empty when the mesh
// itself has no more than that. Triangles the decimater cannot take (a non-manifold fan) stay
// as they are, with their corners kept, so nothing is left out. A big mesh is decimated in
// spatial parts on `threads` threads (0: one per core), then joined and decimated once more
// to the budget; the result is the same on any number of threads, paused or not.
// Returns early, empty, once `signals` (if given) says cancel.
ProxyTriangles decimate_triangles(const MeshTopology& topology, int max_triangles,
                                  const DecimationSignals* signals = nullptr, int threads = 0);

// The proxy built off the window's thread: decimating a 100k-face mesh took about two seconds
// on one core, and a mesh should open at once (it is drawn in full until its proxy is ready).
// Destroying the build cancels it and waits only for the decimater's next check.
// The window pauses it as stand_in_waits says.
class ProxyBuild {
 public:
  ProxyBuild(std::shared_ptr<const MeshTopology> topology, int max_triangles);
  ~ProxyBuild();
  ProxyBuild(const ProxyBuild&) = delete;
  ProxyBuild& operator=(const ProxyBuild&) = delete;

  // The finished proxy (empty for small meshes), or null while it is being built.
  // For one thread at a time (the UI's).
  const ProxyTriangles* ready();
  // Blocks until the proxy is built (tests, screenshots); unpauses it first.
  const ProxyTriangles& wait();
  // Holds the decimation at its next check until unpaused (the same result either way). A
  // build starts paused: a document opens with its first solve ahead, and the window knows
  // from its next frame on whether the cores are free.
  void set_paused(bool paused);

 private:
  DecimationSignals signals_;
  std::future<ProxyTriangles> future_;
  std::optional<ProxyTriangles> result_;
};

// Whether the stand-in's decimation waits, the window's decision every frame. Drawn in
// software, never: motion needs the stand-in (a 240k-face drag started as an opened scenario
// settled showed 4.3-8.4 updates a second while it was decimated beside it, 8.5-9.7 when it
// was made at once; the opened pose then shows about a second later on two cores). On a GPU,
// while the editor settles and nothing moves: the full mesh draws fast there, and the
// decimation beside an opened scenario's first solve takes cores from it.
bool stand_in_waits(bool drawn_in_software, bool editor_settled, bool in_motion);

}  // namespace primo::editor
