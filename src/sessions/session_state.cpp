#include "primo/sessions/session_state.h"

#include <algorithm>

#include "primo/model/falloff_springs.h"

namespace primo {

bool same_factors(const FaceFactors& a, const FaceFactors& b) {
  if (a == b) return true;
  // Null means all 1: compare against an explicit array of ones.
  const FaceFactors& x = a ? a : b;
  const FaceFactors& y = a ? b : a;
  if (!y) return std::all_of(x->begin(), x->end(), [](double v) { return v == 1.0; });
  return *x == *y;
}

namespace {

// What the solver is built from: the faces, how they are held, the falloff, and the stiffness
// of a spring or a falloff.
bool same_handle_structure(const SessionHandle& a, const SessionHandle& b) {
  return same_contents(a.faces, b.faces) && a.mode == b.mode &&
         ((a.mode != SessionHandleMode::Spring && !a.falloff) || a.stiffness == b.stiffness) &&
         same_contents(a.falloff, b.falloff);
}

}  // namespace

RigidTransform SessionHandle::transform() const {
  RigidTransform t;
  t.rotation = pose.rotation.toRotationMatrix();
  t.translation = center + pose.translate - t.rotation * center;
  return t;
}

bool operator==(const SessionState& a, const SessionState& b) {
  if (a.handles.size() != b.handles.size() || !(a.prisms == b.prisms) ||
      !same_factors(a.height_factor, b.height_factor) ||
      !same_factors(a.width_factor, b.width_factor))
    return false;
  for (size_t i = 0; i < a.handles.size(); ++i) {
    const SessionHandle &x = a.handles[i], &y = b.handles[i];
    if (x.name != y.name || !same_handle_structure(x, y) || x.stiffness != y.stiffness ||
        !(x.pose == y.pose) || x.center != y.center)
      return false;
  }
  return true;
}

SessionSolverInputs solver_inputs(const SessionState& state, const FaceGeometry& rest) {
  SessionSolverInputs in;
  in.params.height = state.prisms.height;
  in.params.height_unit = state.prisms.height_unit;
  in.params.width = state.prisms.width;
  in.params.normal_blend = state.prisms.normal_blend;
  if (state.height_factor) in.params.face_height_factor = *state.height_factor;
  if (state.width_factor) in.params.face_width_factor = *state.width_factor;
  for (const SessionHandle& h : state.handles) {
    if (h.mode == SessionHandleMode::Spring) {
      in.forces.push_back({h.name, *h.faces, h.pose.translate, h.stiffness});
      continue;
    }
    Fix fix = Fix::All;
    if (h.mode == SessionHandleMode::Position) fix = Fix::Position;
    if (h.mode == SessionHandleMode::Orientation) fix = Fix::Orientation;
    in.handles.push_back({h.name, *h.faces, fix, h.transform(), h.pose.known_turn()});
  }
  for (const SessionHandle& h : state.handles) {
    if (!h.falloff) continue;
    const RigidTransform motion =
        falloff_motion(h.transform(), h.pose.translate, h.mode == SessionHandleMode::Spring);
    const std::vector<FalloffSpring> springs =
        falloff_springs(rest, h.falloff->faces, h.falloff->weights);
    for (Force& f : falloff_forces(h.name, springs, motion, h.stiffness))
      in.forces.push_back(std::move(f));
  }
  return in;
}

bool same_solver_structure(const SessionState& a, const SessionState& b) {
  if (a.handles.size() != b.handles.size() || !(a.prisms == b.prisms) ||
      !same_factors(a.height_factor, b.height_factor) ||
      !same_factors(a.width_factor, b.width_factor))
    return false;
  for (size_t i = 0; i < a.handles.size(); ++i)
    if (!same_handle_structure(a.handles[i], b.handles[i])) return false;
  return true;
}

}  // namespace primo
