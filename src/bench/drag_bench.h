#pragma once
// `primo bench drag SCENARIO.json [--frames N] [--solver S] [--json FILE] [--mesh MESH]
//                   [--subdivide K] [--bbox-handles] [--drag-only] [hierarchical settings]`
//
// An interactive drag: every handle goes from rest to its scenario transform in N equal steps,
// with one solver iteration (one hierarchical cycle, one global Newton iteration or one local
// sweep) and one read of the vertex positions per frame, as the editor does while a handle is
// dragged. Then the solve continues to convergence, and a fresh deformer solves the final pose
// from rest. The lag is measured as the artist sees it: at checkpoint frames, the largest
// vertex distance between the drag's mesh and the converged shape of that frame's targets (a
// second deformer, converged frame by frame), next to the energy gap. docs/performance.md
// describes every figure.

#include <cstdint>
#include <string>

#include "primo/solve/deformer.h"
#include "primo/solve/hierarchical_solver.h"

namespace primo::bench {

struct DragBenchOptions {
  std::string scenario;
  int frames = 60;
  // Solver iterations a frame: the editor gives a drag's batch as many as fit 50 ms (on this
  // 2-core machine one from about 40,000 faces up; more on faster ones). From two on, the
  // second is a Newton-Krylov step (HierarchicalOptions::newton_krylov_in_frames).
  int frame_iterations = 1;
  std::string solver = "hierarchical";  // "hierarchical", "global" or "local"
  std::string json;
  std::string mesh;  // instead of the scenario's; a bare file name is looked up in shared/meshes
  int subdivide = 0;  // Loop subdivision steps first
  // Then, when not 0, the mesh's vertices and faces renumbered at random from this seed
  // (shuffled_mesh): the same surface as another tool might write it.
  std::uint64_t shuffle = 0;
  bool bbox_handles = false;  // the reach pose (reach_pose.h) instead of the scenario's handles
  bool drag_only = false;  // no convergence afterwards, no full solve: for repeated timings
  // The frames show the drag's preview (Deformer::preview: coarse levels only, as the editor
  // shows a drag on a mesh whose cycles outlast a frame) instead of solving the fine level;
  // the settle after the drag is the full resolution catching up.
  bool preview = false;
  // With preview: every this many frames, a frame at full resolution instead (0: none), from
  // which the next previews carry only the motion since.
  int preview_full_every = 0;
  // Every this many frames (and at the last), how far the drag's mesh is from the shape the
  // solver converges to for that frame's targets: the lag the artist sees. 0: the last frame
  // only (its converged shape is the one the solve after the drag reaches).
  int lag_every = 10;
  // At the same frames, also how far the drag's mesh is from where it settles when the hand
  // stops there (solved on from the frame's state, the targets held): near an instability
  // (a snap-through) that shape and the converged drag's can be different minima.
  bool lag_settle = false;
  // After the settle: the targets back to rest and then to the pose again, each a jump
  // solved as the editor's solver thread solves an undo and a redo.
  bool undo_redo = false;
  double drag_prediction = SolveOptions{}.drag_prediction;  // SolveOptions::drag_prediction
  HierarchicalOptions hierarchical;  // the core's defaults unless the experiment flags say otherwise
};

// Prints the tables; returns the exit code. Throws primo::Error on bad options or files.
int run_drag_bench(const DragBenchOptions& options);

}  // namespace primo::bench
