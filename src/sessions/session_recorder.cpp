#include "primo/sessions/session_recorder.h"

#include <algorithm>

namespace primo {
namespace {

// Anything but the pose changed: the recording needs the whole handle list again.
bool same_handle(const SessionHandle& a, const SessionHandle& b) {
  return a.name == b.name && (a.faces == b.faces || *a.faces == *b.faces) && a.mode == b.mode &&
         a.stiffness == b.stiffness && a.center == b.center && a.color == b.color &&
         same_contents(a.falloff, b.falloff);
}

const FaceFactors& layer_factors(const SessionState& state, FactorLayer layer) {
  return layer == FactorLayer::Height ? state.height_factor : state.width_factor;
}

double factor_at(const FaceFactors& factors, int face) {
  return factors ? (*factors)[size_t(face)] : 1.0;
}

}  // namespace

void SessionRecorder::start(const SessionState& initial, const std::string& mesh_path,
                            const SolverSpec& solver, double now) {
  recording_ = true;
  session_ = Session{};
  session_.mesh_path = mesh_path;
  session_.mesh = mesh_path;
  session_.solver = solver;
  session_.initial = initial;
  last_ = initial;
  t0_ = now;
  frame_ = 0;
}

void SessionRecorder::push(SessionEvent e, double now) {
  e.t = std::max(0.0, now - t0_);
  if (!session_.events.empty()) e.t = std::max(e.t, session_.events.back().t);
  e.frame = frame_;
  session_.events.push_back(std::move(e));
}

void SessionRecorder::note_undo(bool redo, double now) {
  if (!recording_) return;
  SessionEvent e;
  e.type = redo ? SessionEvent::Type::Redo : SessionEvent::Type::Undo;
  push(std::move(e), now);
}

void SessionRecorder::observe(const SessionState& s, int n_faces, double now) {
  if (!recording_) return;
  // 1. Handles: the whole list when anything but poses changed, else the poses that did.
  bool structure = s.handles.size() != last_.handles.size();
  for (size_t i = 0; !structure && i < s.handles.size(); ++i)
    structure = !same_handle(s.handles[i], last_.handles[i]);
  if (structure) {
    SessionEvent e;
    e.type = SessionEvent::Type::Handles;
    e.handles = s.handles;
    push(std::move(e), now);
  } else {
    SessionEvent e;
    e.type = SessionEvent::Type::Targets;
    for (size_t i = 0; i < s.handles.size(); ++i)
      if (!(s.handles[i].pose == last_.handles[i].pose)) e.poses.push_back({int(i), s.handles[i].pose});
    if (!e.poses.empty()) push(std::move(e), now);
  }
  // 2. Painted factors: the faces whose value changed (arrays are shared until they change).
  for (FactorLayer layer : {FactorLayer::Height, FactorLayer::Width}) {
    const FaceFactors& now_f = layer_factors(s, layer);
    const FaceFactors& was_f = layer_factors(last_, layer);
    if (now_f == was_f) continue;
    SessionEvent e;
    e.type = SessionEvent::Type::Factors;
    e.layer = layer;
    for (int f = 0; f < n_faces; ++f) {
      const double v = factor_at(now_f, f);
      if (v != factor_at(was_f, f)) e.faces.push_back(f), e.values.push_back(v);
    }
    if (!e.faces.empty()) push(std::move(e), now);
  }
  // 3. Prism settings.
  if (!(s.prisms == last_.prisms)) {
    SessionEvent e;
    e.type = SessionEvent::Type::Prisms;
    e.prisms = s.prisms;
    push(std::move(e), now);
  }
  last_ = s;
  ++frame_;
}

Session SessionRecorder::stop() {
  recording_ = false;
  return session_;
}

}  // namespace primo
