#include "session_replay.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "primo/error.h"
#include "solver_worker.h"

namespace primo::editor {
namespace {

std::unique_ptr<Deformer> build(const Mesh& mesh, const EditState& state, const Deformer* previous) {
  const DeformationInputs in = deformation_inputs(state);
  auto d = std::make_unique<Deformer>(mesh, in.params, in.handles, in.forces);
  if (previous) d->set_face_motions(previous->face_motions());
  return d;
}

void set_targets(Deformer& d, const EditState& state) {
  const DeformationInputs in = deformation_inputs(state);
  for (size_t h = 0; h < in.handles.size(); ++h) d.set_handle_transform(int(h), in.handles[h].transform);
  for (size_t f = 0; f < in.forces.size(); ++f)
    if (in.forces[f].target_offset != d.forces()[f].target_offset)
      d.set_force_offset(int(f), in.forces[f].target_offset);
}

SolveOptions options_for(const SolverSpec& spec, int n_faces, int max_iterations) {
  SolveOptions o;
  o.method = interactive_solve_method(spec.method, n_faces);
  o.tolerance = spec.tolerance;
  o.max_iterations = max_iterations;
  return o;
}

}  // namespace

ReplayResult replay_session(const Session& session, const Mesh& mesh, const ReplayOptions& opt) {
  const int n_faces = int(mesh.n_faces());
  validate_session(session, n_faces);  // throws naming the event; nothing solved yet

  ReplayResult r;
  EditState state = validate_session(Session{session.source, session.mesh, session.mesh_path,
                                             session.solver, session.initial, {}},
                                     n_faces);
  std::unique_ptr<Deformer> d = build(mesh, state, nullptr);
  bool converged = false;
  size_t next = 0;
  const int frames = session.frames();
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    const EditState before = state;
    while (next < session.events.size() && session.events[next].frame == frame)
      apply_event(state, session.events[next++], n_faces);
    if (!same_structure(before, state)) {
      d = build(mesh, state, d.get());
      ++r.rebuilds;
      converged = false;
    } else if (!(before == state)) {
      set_targets(*d, state);
      converged = false;
    }
    if (!converged && opt.iterations_per_frame > 0) {
      const SolveReport rep = d->solve(options_for(session.solver, n_faces, opt.iterations_per_frame));
      r.iterations += rep.iterations;
      converged = rep.converged && rep.stop_reason == "tolerance";
    }
    if (opt.every > 0 && frame % opt.every == 0 && opt.on_frame) opt.on_frame(frame, *d);
  }
  r.frames = std::max(frames, 1);

  // Settle, confirmed by one more solve after a stop on the tolerance.
  for (int pass = 0; pass < 2; ++pass) {
    const SolveReport rep = d->solve(options_for(session.solver, n_faces, session.solver.max_iterations));
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

std::vector<Vec3> solve_from_rest(const EditState& state, const Mesh& mesh, const SolverSpec& spec) {
  std::unique_ptr<Deformer> d = build(mesh, state, nullptr);
  for (int pass = 0; pass < 2; ++pass)
    if (!d->solve(options_for(spec, int(mesh.n_faces()), spec.max_iterations)).converged) break;
  return d->vertex_positions();
}

}  // namespace primo::editor

namespace primo::editor {
namespace {

std::vector<Vec3> centroids(const Mesh& mesh) {
  std::vector<Vec3> c;
  c.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    Vec3 s = Vec3::Zero();
    int n = 0;
    for (auto v : mesh.fv_range(f)) s += mesh.point(v), ++n;
    c.push_back(s / double(std::max(n, 1)));
  }
  return c;
}

}  // namespace

Session map_session_to_mesh(const Session& session, const Mesh& coarse, const Mesh& fine) {
  validate_session(session, int(coarse.n_faces()));
  const std::vector<Vec3> cc = centroids(coarse), fc = centroids(fine);
  // Fine faces of each coarse face (brute force: fine enough for editor-sized meshes).
  std::vector<std::vector<int>> children(cc.size());
  for (size_t f = 0; f < fc.size(); ++f) {
    size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < cc.size(); ++c) {
      const double d = (cc[c] - fc[f]).squaredNorm();
      if (d < best_d) best_d = d, best = c;
    }
    children[best].push_back(int(f));
  }
  auto map_groups = [&](std::vector<HandleGroup>& groups) {
    for (HandleGroup& g : groups) {
      std::vector<int> faces;
      for (int c : *g.faces) faces.insert(faces.end(), children[size_t(c)].begin(), children[size_t(c)].end());
      std::sort(faces.begin(), faces.end());
      if (faces.empty()) throw Error("handle '" + g.name + "' has no face on the finer mesh");
      g.faces = std::make_shared<const std::vector<int>>(std::move(faces));
    }
  };
  auto map_factors = [&](FactorArray& f) {
    if (!f) return;
    auto a = std::make_shared<std::vector<double>>(fc.size(), 1.0);
    for (size_t c = 0; c < f->size() && c < children.size(); ++c)
      for (int x : children[c]) (*a)[size_t(x)] = (*f)[c];
    f = a;
  };
  Session s = session;
  map_groups(s.initial.handles);
  map_factors(s.initial.height_factor);
  map_factors(s.initial.width_factor);
  for (SessionEvent& e : s.events) {
    if (e.type == SessionEvent::Type::Handles) map_groups(e.handles);
    if (e.type == SessionEvent::Type::Factors) {
      std::vector<std::pair<int, double>> fv;
      for (size_t i = 0; i < e.faces.size(); ++i)
        for (int x : children[size_t(e.faces[i])]) fv.push_back({x, e.values[i]});
      std::sort(fv.begin(), fv.end());
      e.faces.clear(), e.values.clear();
      for (const auto& [f, v] : fv) e.faces.push_back(f), e.values.push_back(v);
    }
  }
  return s;
}

}  // namespace primo::editor
