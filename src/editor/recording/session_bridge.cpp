#include "session_bridge.h"

namespace primo::editor {

SessionHandleMode session_mode(HandleMode mode) {
  switch (mode) {
    case HandleMode::Pose: return SessionHandleMode::Pose;
    case HandleMode::Position: return SessionHandleMode::Position;
    case HandleMode::Orientation: return SessionHandleMode::Orientation;
    case HandleMode::Spring: return SessionHandleMode::Spring;
    case HandleMode::Fixed: return SessionHandleMode::Fixed;
  }
  return SessionHandleMode::Pose;
}

HandleMode handle_mode(SessionHandleMode mode) {
  switch (mode) {
    case SessionHandleMode::Pose: return HandleMode::Pose;
    case SessionHandleMode::Position: return HandleMode::Position;
    case SessionHandleMode::Orientation: return HandleMode::Orientation;
    case SessionHandleMode::Spring: return HandleMode::Spring;
    case SessionHandleMode::Fixed: return HandleMode::Fixed;
  }
  return HandleMode::Pose;
}

SessionHandle session_handle(const HandleGroup& g) {
  SessionHandle h;
  h.name = g.name;
  h.faces = g.faces;
  h.mode = session_mode(g.mode);
  h.stiffness = g.stiffness;
  h.center = g.center;
  h.pose.translate = g.pose.translate;
  h.pose.rotation = g.pose.rotation;
  h.pose.turn = g.pose.turn;
  h.color = g.color;
  if (g.falloff_radius > 0.0) {
    auto falloff = std::make_shared<SessionFalloff>();
    falloff->radius = g.falloff_radius;
    if (g.falloff)
      for (const FalloffFace& f : *g.falloff)
        falloff->faces.push_back(f.face), falloff->weights.push_back(f.weight);
    h.falloff = falloff;
  }
  return h;
}

HandleGroup handle_group(const SessionHandle& h, const FaceGeometry& rest) {
  HandleGroup g;
  g.name = h.name;
  g.faces = h.faces;
  g.mode = handle_mode(h.mode);
  g.stiffness = h.stiffness;
  g.center = h.center;
  g.pose.translate = h.pose.translate;
  g.pose.rotation = h.pose.rotation;
  g.pose.turn = h.pose.turn;
  g.color = h.color;
  if (h.falloff) {
    g.falloff_radius = h.falloff->radius;
    if (!h.falloff->faces.empty())
      g.falloff = std::make_shared<const std::vector<FalloffFace>>(
          falloff_springs(rest, h.falloff->faces, h.falloff->weights));
  }
  return g;
}

SessionState session_state(const EditState& state) {
  SessionState s;
  s.handles.reserve(state.handles.size());
  for (const HandleGroup& g : state.handles) s.handles.push_back(session_handle(g));
  s.prisms.height = state.prisms.height;
  s.prisms.height_unit = state.prisms.height_unit;
  s.prisms.width = state.prisms.width;
  s.prisms.normal_blend = state.prisms.normal_blend;
  s.height_factor = state.height_factor;
  s.width_factor = state.width_factor;
  return s;
}

void set_session_state(EditState& state, const SessionState& session, const FaceGeometry& rest) {
  state.handles.clear();
  state.handles.reserve(session.handles.size());
  for (const SessionHandle& h : session.handles) state.handles.push_back(handle_group(h, rest));
  state.prisms.height = session.prisms.height;
  state.prisms.height_unit = session.prisms.height_unit;
  state.prisms.width = session.prisms.width;
  state.prisms.normal_blend = session.prisms.normal_blend;
  state.height_factor = session.height_factor;
  state.width_factor = session.width_factor;
}

}  // namespace primo::editor
