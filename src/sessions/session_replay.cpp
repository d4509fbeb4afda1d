#include "primo/sessions/session_replay.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "primo/util/error.h"
#include "primo/scenario/scenario_solve.h"

namespace primo {
namespace {

std::unique_ptr<Deformer> build(const Mesh& mesh, const FaceGeometry& rest,
                                const SessionState& state, const Deformer* previous) {
  const SessionSolverInputs in = solver_inputs(state, rest);
  auto d = std::make_unique<Deformer>(mesh, in.params, in.handles, in.forces);
  if (previous) d->set_face_motions(previous->face_motions());
  return d;
}

void set_targets(Deformer& d, const FaceGeometry& rest, const SessionState& state) {
  const SessionSolverInputs in = solver_inputs(state, rest);
  for (size_t h = 0; h < in.handles.size(); ++h)
    d.set_handle_transform(int(h), in.handles[h].transform, in.handles[h].turn);
  for (size_t f = 0; f < in.forces.size(); ++f)
    if (in.forces[f].target_offset != d.forces()[f].target_offset)
      d.set_force_offset(int(f), in.forces[f].target_offset);
}

SolveOptions options_for(const SolverSpec& spec, int n_faces, int max_iterations,
                         bool drag_frame = false) {
  SolveOptions o;
  o.method = scenario_solve_method(spec.method, size_t(n_faces));  // as the editor solves
  o.tolerance = spec.tolerance;
  o.max_iterations = max_iterations;
  o.drag_frame = drag_frame;
  return o;
}

}  // namespace

ReplayResult replay_session(const Session& session, const Mesh& mesh, const ReplayOptions& opt) {
  const int n_faces = int(mesh.n_faces());
  validate_session(session, n_faces);  // throws naming the event; nothing solved yet

  ReplayResult r;
  SessionState state = initial_state(session, n_faces);
  const FaceGeometry rest = compute_face_geometry(mesh);
  std::unique_ptr<Deformer> d = build(mesh, rest, state, nullptr);
  bool converged = false;
  size_t next = 0;
  const int frames = session.frames();
  // Iterations since the state last changed: a stretch of frames without events (a session may
  // be idle for 10 million frames) is solved for at most solver.max_iterations iterations, as a
  // settle would be; the frames after that, and every frame once converged, change nothing and
  // are skipped unless frames are exported.
  long idle_iterations = 0;
  const bool exporting = opt.every > 0 && opt.on_frame;
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    if ((converged || idle_iterations >= session.solver.max_iterations) && !exporting) {
      const int next_frame = next < session.events.size() ? session.events[next].frame : frames;
      if (next_frame >= frames) break;
      frame = std::max(frame, next_frame);
    }
    const SessionState before = state;
    while (next < session.events.size() && session.events[next].frame == frame)
      apply_event(state, session.events[next++], n_faces);
    const bool changed = !(before == state);
    if (!same_solver_structure(before, state)) {
      d = build(mesh, rest, state, d.get());
      ++r.rebuilds;
      converged = false;
    } else if (changed) {
      set_targets(*d, rest, state);
      converged = false;
    }
    if (changed) idle_iterations = 0;
    if (!converged && idle_iterations < session.solver.max_iterations &&
        opt.iterations_per_frame > 0) {
      // A frame whose events changed anything is solved as the editor's batch while dragging
      // (SolveOptions::drag_frame: with two iterations or more, a cycle and a Newton-Krylov step).
      const SolveReport rep =
          d->solve(options_for(session.solver, n_faces, opt.iterations_per_frame, changed));
      r.iterations += rep.iterations;
      idle_iterations += std::max(rep.iterations, 1);
      converged = rep.converged && rep.stop_reason == "tolerance";
    }
    if (opt.every > 0 && frame % opt.every == 0 && opt.on_frame) opt.on_frame(frame, *d);
  }
  r.frames = std::max(frames, 1);

  // Settle, confirmed by one more solve after a stop on the tolerance.
  for (int pass = 0; pass < 2; ++pass) {
    const SolveReport rep =
        d->solve(options_for(session.solver, n_faces, session.solver.max_iterations));
    r.iterations += rep.iterations;
    r.converged = rep.converged;
    r.energy = rep.energy;
    if (!rep.converged) break;
  }
  r.positions = d->vertex_positions();
  for (size_t v = 0; v < r.positions.size(); ++v)
    if (!r.positions[v].allFinite())
      throw Error((session.source.empty() ? std::string("session") : session.source) +
                  ": the replay produced a non-finite position at vertex " + std::to_string(v));
  r.state = state;
  return r;
}

std::vector<Vec3> solve_from_rest(const SessionState& state, const Mesh& mesh,
                                  const SolverSpec& spec) {
  std::unique_ptr<Deformer> d = build(mesh, compute_face_geometry(mesh), state, nullptr);
  for (int pass = 0; pass < 2; ++pass)
    if (!d->solve(options_for(spec, int(mesh.n_faces()), spec.max_iterations)).converged) break;
  return d->vertex_positions();
}

}  // namespace primo
