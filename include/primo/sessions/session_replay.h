#pragma once
// Headless replay of a recorded session (`primo replay`, docs/sessions.md). Deterministic:
// the same session on the same mesh gives bitwise the same meshes.
//
// Frame by frame, from frame 0 to the last recorded frame: the frame's events are applied to
// the state; when the structure changed (handles created/deleted/re-moded, factors or prism
// settings) the Deformer is rebuilt keeping the current face motions (as the editor's solver
// thread does), otherwise the new handle targets are set; then `iterations_per_frame` solver
// iterations run, warm-started (skipped once converged and nothing changed since), as a drag's
// frame when the frame's events changed anything (SolveOptions::drag_frame). After the
// last frame the state is settled: solves up to the session's solver.max_iterations until the
// tolerance is met, confirmed by one more solve (as the editor's settle), so the final mesh is
// the converged pose the editor shows at the end of the session.

#include <functional>
#include <vector>

#include "primo/solve/deformer.h"
#include "primo/mesh/mesh.h"
#include "primo/sessions/session.h"

namespace primo {

struct ReplayOptions {
  int iterations_per_frame = 1;
  // Called after frame f's solve when f % every == 0 (every > 0), and never otherwise.
  int every = 0;
  std::function<void(int frame, const Deformer& deformer)> on_frame;
};

struct ReplayResult {
  std::vector<Vec3> positions;  // final deformed vertices
  SessionState state;           // final state
  int frames = 0;
  int rebuilds = 0;
  long iterations = 0;
  bool converged = false;
  double energy = 0.0;
};

// Validates the session against `mesh` first (throws primo::Error naming the event, before any
// solve), then replays it.
ReplayResult replay_session(const Session& session, const Mesh& mesh, const ReplayOptions& options = {});

// The state solved from rest with a fresh Deformer to the session's tolerance: what
// `primo deform` gives for the scenario the editor would export at the end.
std::vector<Vec3> solve_from_rest(const SessionState& state, const Mesh& mesh, const SolverSpec& spec);

}  // namespace primo
